#include "offline/sim/strict_json.hpp"

#include <cmath>
#include <sstream>

#include "tpf/common/error.hpp"

namespace tpf::offline {

namespace {
std::string format(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}
}  // namespace

StrictObject::StrictObject(const nlohmann::json& object, std::string file, std::string path)
    : object_(object), file_(std::move(file)), path_(std::move(path)) {
  if (!object_.is_object())
    throw Error::at(file_, 0, path_.empty() ? "(top level)" : path_, "must be a JSON object");
}

std::string StrictObject::key_path(const std::string& key) const {
  return path_.empty() ? key : path_ + "." + key;
}

void StrictObject::fail(const std::string& key, const std::string& message) const {
  throw Error::at(file_, 0, key_path(key), message);
}

const nlohmann::json& StrictObject::get(const std::string& key) {
  used_.insert(key);
  return object_.at(key);
}

double StrictObject::number(const std::string& key, double fallback, double lo, double hi) {
  if (!object_.contains(key)) return fallback;
  return number(key, lo, hi);
}

double StrictObject::number(const std::string& key, double lo, double hi) {
  if (!object_.contains(key)) fail(key, "missing");
  const auto& v = get(key);
  if (!v.is_number()) fail(key, "must be a number");
  const double x = v.get<double>();
  if (!std::isfinite(x) || x < lo || x > hi)
    fail(key, "must be in [" + format(lo) + ", " + format(hi) + "], got " + format(x));
  return x;
}

std::vector<double> StrictObject::numbers(const std::string& key, std::vector<double> fallback,
                                          double lo, double hi, std::size_t size) {
  if (!object_.contains(key)) return fallback;
  const auto& v = get(key);
  if (!v.is_array() || v.size() != size)
    fail(key, "must be an array of " + std::to_string(size) + " numbers");
  std::vector<double> out;
  for (std::size_t i = 0; i < size; ++i) {
    const std::string item = key + "[" + std::to_string(i) + "]";
    if (!v[i].is_number()) fail(item, "must be a number");
    const double x = v[i].get<double>();
    if (!std::isfinite(x) || x < lo || x > hi)
      fail(item, "must be in [" + format(lo) + ", " + format(hi) + "], got " + format(x));
    out.push_back(x);
  }
  return out;
}

bool StrictObject::boolean(const std::string& key, bool fallback) {
  if (!object_.contains(key)) return fallback;
  const auto& v = get(key);
  if (!v.is_boolean()) fail(key, "must be true or false");
  return v.get<bool>();
}

std::string StrictObject::text(const std::string& key, std::string fallback) {
  if (!object_.contains(key)) return fallback;
  const auto& v = get(key);
  if (!v.is_string()) fail(key, "must be a string");
  return v.get<std::string>();
}

std::string StrictObject::choice(const std::string& key, std::string fallback,
                                 const std::vector<std::string>& choices) {
  const std::string v = text(key, std::move(fallback));
  for (const auto& c : choices)
    if (c == v) return v;
  std::string list;
  for (const auto& c : choices)
    list += (list.empty() ? "" : ", ") + c;
  fail(key, "must be one of " + list + ", got \"" + v + "\"");
}

StrictObject StrictObject::child(const std::string& key) {
  if (!object_.contains(key)) return StrictObject(nlohmann::json::object(), file_, key_path(key));
  return StrictObject(get(key), file_, key_path(key));
}

std::vector<StrictObject> StrictObject::children(const std::string& key) {
  std::vector<StrictObject> out;
  if (!object_.contains(key)) return out;
  const auto& v = get(key);
  if (!v.is_array()) fail(key, "must be an array of objects");
  for (std::size_t i = 0; i < v.size(); ++i)
    out.emplace_back(v[i], file_, key_path(key) + "[" + std::to_string(i) + "]");
  return out;
}

void StrictObject::finish() const {
  for (const auto& [key, value] : object_.items())
    if (!used_.count(key)) fail(key, "unknown key");
}

}  // namespace tpf::offline
