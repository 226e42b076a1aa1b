#include "offline/log/log_metadata.hpp"

#include <charconv>
#include <cmath>
#include <limits>

#include "tpf/common/error.hpp"

namespace tpf::offline {

std::optional<std::string> LogMetadata::get(std::string_view key) const {
  for (const auto& [k, v] : entries)
    if (k == key) return v;
  return std::nullopt;
}

void LogMetadata::set(std::string key, std::string value) {
  for (auto& [k, v] : entries) {
    if (k == key) {
      v = std::move(value);
      return;
    }
  }
  entries.emplace_back(std::move(key), std::move(value));
}

int LogMetadata::version() const {
  const auto text = get("tpf-log");
  if (!text) return 1;
  int major = 0;
  const char* end = text->data() + text->size();
  const auto [ptr, ec] = std::from_chars(text->data(), end, major);
  if (ec != std::errc{} || major < 0 || (ptr != end && *ptr != '.'))
    throw Error("tpf-log: '" + *text + "' is not a version number");
  return major;
}

double LogMetadata::rate_hz() const {
  const auto text = get("rate_hz");
  if (!text) return std::numeric_limits<double>::quiet_NaN();
  double rate = 0.0;
  const char* end = text->data() + text->size();
  const auto [ptr, ec] = std::from_chars(text->data(), end, rate);
  if (ec != std::errc{} || ptr != end || !std::isfinite(rate) || rate <= 0.0)
    throw Error("rate_hz: '" + *text + "' is not a positive number");
  return rate;
}

}  // namespace tpf::offline
