#include "option_validators.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

#include "core/common/unoptimised_when_sanitized.hpp"

TPF_UNOPTIMISED_WHEN_SANITIZED_BEGIN

namespace tpf::cli {
namespace {

std::string number_text(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

/// "in (0, 1e+06]", "> 0", "≥ 1", "in [0, 1)".
std::string describe(const Interval& i) {
  const bool has_low = i.low > -std::numeric_limits<double>::max();
  const bool has_high = i.high < std::numeric_limits<double>::max();
  if (has_low && has_high)
    return std::string("in ") + (i.low_open ? "(" : "[") + number_text(i.low) + ", " +
           number_text(i.high) + (i.high_open ? ")" : "]");
  if (has_low) return (i.low_open ? "> " : "≥ ") + number_text(i.low);
  if (has_high) return (i.high_open ? "< " : "≤ ") + number_text(i.high);
  return "finite";
}

bool inside(const Interval& i, double value) {
  const bool above = i.low_open ? value > i.low : value >= i.low;
  const bool below = i.high_open ? value < i.high : value <= i.high;
  return std::isfinite(value) && above && below;
}

/// "<path> is a directory, not a file", or empty.
std::string directory_problem(const std::string& path) {
  std::error_code error;
  return std::filesystem::is_directory(path, error) ? path + " is a directory, not a file"
                                                    : std::string();
}

}  // namespace

CLI::Validator number_in(const Interval& interval) {
  const std::string expected = "a number " + describe(interval);
  return {[interval, expected](std::string& text) -> std::string {
            double value = 0.0;
            if (!CLI::detail::lexical_cast(text, value)) return {};  // CLI11 names the option
            if (inside(interval, value)) return {};
            return text + (std::isfinite(value) ? " is out of range" : " is not a finite number") +
                   "; expected " + expected;
          },
          describe(interval)};
}

CLI::Validator one_of(std::initializer_list<int> values) {
  std::string listed;
  for (int v : values)
    listed += (listed.empty() ? "" : " or ") + std::to_string(v);
  return {[allowed = std::vector<int>(values), listed](std::string& text) -> std::string {
            long value = 0;
            if (!CLI::detail::lexical_cast(text, value)) return {};  // CLI11 names the option
            for (int v : allowed)
              if (value == v) return {};
            return text + " is not allowed; expected " + listed;
          },
          listed};
}

CLI::Validator input_file() {
  return {[](std::string& path) {
            const std::string problem = directory_problem(path);
            return problem.empty() ? CLI::ExistingFile(path) : problem;
          },
          "FILE"};
}

CLI::Validator input_file_or(const char* keyword) {
  const std::string word = keyword;
  return {[word](std::string& path) { return path == word ? std::string() : input_file()(path); },
          "FILE or " + word};
}

CLI::Validator weights_path() {
  return {[](std::string& path) { return directory_problem(path); }, "PATH"};
}

}  // namespace tpf::cli

TPF_UNOPTIMISED_WHEN_SANITIZED_END
