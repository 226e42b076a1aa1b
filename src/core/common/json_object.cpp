#include "core/common/json_object.hpp"

#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include "core/common/json_parse.hpp"
#include "core/common/unoptimised_when_sanitized.hpp"
#include "tpf/common/error.hpp"

TPF_UNOPTIMISED_WHEN_SANITIZED_BEGIN

namespace tpf::json {

namespace {
std::string format(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}
}  // namespace

Object::Object(const nlohmann::json& object, std::string file, std::string path)
    : object_(object), file_(std::move(file)), path_(std::move(path)) {
  if (!object_.is_object())
    throw Error::at(file_, 0, path_.empty() ? "(top level)" : path_, "must be a JSON object");
}

std::string Object::key_path(const std::string& key) const {
  return path_.empty() ? key : path_ + "." + key;
}

void Object::fail(const std::string& key, const std::string& message) const {
  throw Error::at(file_, 0, key_path(key), message);
}

const nlohmann::json& Object::get(const std::string& key) {
  used_.insert(key);
  return object_.at(key);
}

double Object::number(const std::string& key, double fallback, double lo, double hi) {
  if (!object_.contains(key)) return fallback;
  return number(key, lo, hi);
}

double Object::number(const std::string& key, double lo, double hi) {
  if (!object_.contains(key)) fail(key, "missing");
  const auto& v = get(key);
  if (!v.is_number()) fail(key, "must be a number");
  const double x = v.get<double>();
  if (!std::isfinite(x) || x < lo || x > hi)
    fail(key, "must be in [" + format(lo) + ", " + format(hi) + "], got " + format(x));
  return x;
}

std::vector<double> Object::numbers(const std::string& key, std::vector<double> fallback, double lo,
                                    double hi, std::size_t size) {
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

std::vector<double> Object::numbers(const std::string& key, double lo, double hi,
                                    std::size_t size) {
  if (!object_.contains(key)) fail(key, "missing");
  return numbers(key, {}, lo, hi, size);
}

Eigen::Vector3d Object::vector3(const std::string& key) {
  const std::vector<double> v = numbers(key, -std::numeric_limits<double>::infinity(),
                                        std::numeric_limits<double>::infinity(), 3);
  return {v[0], v[1], v[2]};
}

void Object::check_bound(const std::string& item, double value, Bound bound) const {
  if (bound == Bound::kPositive && !(value > 0.0))
    fail(item, "must be > 0 (positive), got " + format(value));
  if (bound == Bound::kNonNegative && !(value >= 0.0))
    fail(item, "must be >= 0 (non-negative), got " + format(value));
}

std::vector<std::vector<double>> Object::number_rows(const std::string& key, std::size_t rows,
                                                     std::size_t cols) {
  if (!object_.contains(key)) fail(key, "missing");
  const auto& v = get(key);
  if (!v.is_array() || v.size() != rows)
    fail(key, "must be an array of " + std::to_string(rows) + " rows");
  std::vector<std::vector<double>> out(rows);
  for (std::size_t r = 0; r < rows; ++r) {
    const std::string row = key + "[" + std::to_string(r) + "]";
    if (!v[r].is_array() || v[r].size() != cols)
      fail(row, "must be an array of " + std::to_string(cols) + " numbers");
    for (std::size_t c = 0; c < cols; ++c) {
      const std::string item = row + "[" + std::to_string(c) + "]";
      if (!v[r][c].is_number() || !std::isfinite(v[r][c].get<double>()))
        fail(item, "must be a finite number");
      out[r].push_back(v[r][c].get<double>());
    }
  }
  return out;
}

int Object::integer(const std::string& key, int lo, int hi) {
  const double x = number(key, lo, hi);
  if (x != std::floor(x)) fail(key, "must be a whole number, got " + format(x));
  return static_cast<int>(x);
}

int Object::joint_count_of(const std::string& key) {
  if (!has(key)) fail(key, "missing");
  const nlohmann::json& v = get(key);
  if (!v.is_array() || v.empty() || v.size() > static_cast<std::size_t>(kMaxArrayJoints))
    fail(key,
         "must be an array of 1 to " + std::to_string(kMaxArrayJoints) + " numbers, one per joint");
  return static_cast<int>(v.size());
}

void Object::require_joints(int expected) {
  const int joints = integer("joints", 1, 64);
  if (joints != expected)
    fail("joints",
         "the file is for " + std::to_string(joints) + " joints, the arm here has " +
             std::to_string(expected) +
             " (as its robot file or the log's joint columns say): a file of another arm?");
}

std::string Object::text(const std::string& key) {
  if (!object_.contains(key)) fail(key, "missing");
  return text(key, "");
}

std::vector<std::string> Object::texts(const std::string& key, std::size_t size) {
  if (!object_.contains(key)) fail(key, "missing");
  const auto& v = get(key);
  if (!v.is_array() || v.size() != size)
    fail(key, "must be an array of " + std::to_string(size) + " strings");
  std::vector<std::string> out;
  for (std::size_t i = 0; i < size; ++i) {
    if (!v[i].is_string()) fail(key + "[" + std::to_string(i) + "]", "must be a string");
    out.push_back(v[i].get<std::string>());
  }
  return out;
}

Object Object::read_file(const std::filesystem::path& path) {
  return Object(json::parse_file(path), path.string(), "");
}

Object Object::read_document(const std::filesystem::path& path, std::string_view format,
                             int max_version) {
  Object top = read_file(path);
  const std::string got = top.text("format");
  if (got != format) top.fail("format", "is '" + got + "', expected '" + std::string(format) + "'");
  const double version = top.number("version", 0, 1e9);
  if (version > max_version)
    top.fail("version", "is " + std::to_string(static_cast<long>(version)) +
                            "; this tpf reads up to version " + std::to_string(max_version));
  return top;
}

bool Object::boolean(const std::string& key, bool fallback) {
  if (!object_.contains(key)) return fallback;
  const auto& v = get(key);
  if (!v.is_boolean()) fail(key, "must be true or false");
  return v.get<bool>();
}

std::string Object::text(const std::string& key, std::string fallback) {
  if (!object_.contains(key)) return fallback;
  const auto& v = get(key);
  if (!v.is_string()) fail(key, "must be a string");
  return v.get<std::string>();
}

std::string Object::choice(const std::string& key, std::string fallback,
                           const std::vector<std::string>& choices) {
  const std::string v = text(key, std::move(fallback));
  for (const auto& c : choices)
    if (c == v) return v;
  std::string list;
  for (const auto& c : choices)
    list += (list.empty() ? "" : ", ") + c;
  fail(key, "must be one of " + list + ", got \"" + v + "\"");
}

Object Object::child(const std::string& key) {
  if (!object_.contains(key)) return Object(nlohmann::json::object(), file_, key_path(key));
  return Object(get(key), file_, key_path(key));
}

std::vector<Object> Object::children(const std::string& key) {
  std::vector<Object> out;
  if (!object_.contains(key)) return out;
  const auto& v = get(key);
  if (!v.is_array()) fail(key, "must be an array of objects");
  for (std::size_t i = 0; i < v.size(); ++i)
    out.emplace_back(v[i], file_, key_path(key) + "[" + std::to_string(i) + "]");
  return out;
}

void Object::finish() const {
  for (const auto& [key, value] : object_.items())
    if (!used_.count(key)) fail(key, "unknown key");
}

}  // namespace tpf::json

TPF_UNOPTIMISED_WHEN_SANITIZED_END
