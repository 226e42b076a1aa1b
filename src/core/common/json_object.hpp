// Strict reading of the project's JSON files (robot, pads, friction, parameters, weights,
// scenarios): every key must be known, every number finite and in range; errors name the file and
// the full key path ("joints[2].gear_ratio"). Start-up and offline code only (allocates, throws
// tpf::Error).
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "tpf/common/error.hpp"

namespace tpf::json {

class Object {
 public:
  /// `path` is the key path of this object inside the file ("" for the top level).
  Object(const nlohmann::json& object, std::string file, std::string path);

  /// Reads the JSON file `path` (its top level must be an object). A syntax error names the line.
  static Object read_file(const std::filesystem::path& path);
  /// Reads `path`, checks `"format": format` and `"version" <= max_version`, and returns the top
  /// level. A syntax error names the line.
  static Object read_document(const std::filesystem::path& path, std::string_view format,
                              int max_version);

  /// A number in [lo, hi]; `fallback` when absent.
  double number(const std::string& key, double fallback, double lo, double hi);
  /// A required number in [lo, hi].
  double number(const std::string& key, double lo, double hi);
  /// An array of exactly `size` numbers in [lo, hi]; `fallback` when absent.
  std::vector<double> numbers(const std::string& key, std::vector<double> fallback, double lo,
                              double hi, std::size_t size);
  /// A required array of exactly `size` numbers in [lo, hi].
  std::vector<double> numbers(const std::string& key, double lo, double hi, std::size_t size);
  /// A required [x, y, z] of finite numbers.
  Eigen::Vector3d vector3(const std::string& key);
  /// Lower bound of joint_vector entries; the message says "must be >= 0 (non-negative)" etc.
  enum class Bound { kAny, kNonNegative, kPositive };
  /// An array of exactly out.size() numbers into `out` (unchanged when absent and not required).
  template <int N>
  void joint_vector(const std::string& key, Eigen::Matrix<double, N, 1>& out, bool required,
                    Bound bound = Bound::kAny) {
    if (!required && !has(key)) return;
    const int n = static_cast<int>(out.size());
    const std::vector<double> v = numbers(key, -kInfinity, kInfinity, n);
    for (int i = 0; i < n; ++i) {
      check_bound(key + "[" + std::to_string(i) + "]", v[i], bound);
      out[i] = v[i];
    }
  }
  /// A required array of out.size() upper limits into `out`: each a positive number, or null for
  /// "no limit" (+∞; JSON has no infinity).
  template <int N>
  void joint_limits(const std::string& key, Eigen::Matrix<double, N, 1>& out) {
    if (!has(key)) fail(key, "missing");
    const nlohmann::json& v = get(key);
    const int n = static_cast<int>(out.size());
    if (!v.is_array() || v.size() != static_cast<std::size_t>(n))
      fail(key, "must be an array of " + std::to_string(n) + " numbers or nulls");
    for (int i = 0; i < n; ++i) {
      const std::string item = key + "[" + std::to_string(i) + "]";
      if (v[i].is_null()) {
        out[i] = kInfinity;
        continue;
      }
      if (!v[i].is_number() || !std::isfinite(v[i].get<double>()))
        fail(item, "must be a number or null (no limit)");
      check_bound(item, v[i].get<double>(), Bound::kPositive);
      out[i] = v[i].get<double>();
    }
  }
  /// An array of out.rows() rows of as many numbers into `out` (unchanged when absent).
  template <int N>
  void joint_matrix(const std::string& key, Eigen::Matrix<double, N, N>& out) {
    if (!has(key)) return;
    const std::size_t n = static_cast<std::size_t>(out.rows());
    const std::vector<std::vector<double>> rows = number_rows(key, n, n);
    for (std::size_t r = 0; r < n; ++r)
      for (std::size_t c = 0; c < n; ++c)
        out(r, c) = rows[r][c];
  }
  /// A required array of `rows` arrays of `cols` finite numbers.
  std::vector<std::vector<double>> number_rows(const std::string& key, std::size_t rows,
                                               std::size_t cols);
  /// The length of the required array `key`, as a joint count: 1 … kMaxArrayJoints (an arm's
  /// joint count where a file does not state it).
  int joint_count_of(const std::string& key);
  static constexpr int kMaxArrayJoints = 64;
  /// A required whole number in [lo, hi].
  int integer(const std::string& key, int lo, int hi);
  /// The file's "joints" count, which must be `expected` (the program's compile-time N).
  void require_joints(int expected);
  bool boolean(const std::string& key, bool fallback);
  /// A required string.
  std::string text(const std::string& key);
  std::string text(const std::string& key, std::string fallback);
  /// One of `choices`.
  std::string choice(const std::string& key, std::string fallback,
                     const std::vector<std::string>& choices);
  bool has(const std::string& key) const { return object_.contains(key); }
  /// Whether `key` is present and holds an array (for keys that take one value or one per item).
  bool is_array(const std::string& key) const {
    return object_.contains(key) && object_.at(key).is_array();
  }
  /// A required array of exactly `size` strings.
  std::vector<std::string> texts(const std::string& key, std::size_t size);
  /// A nested object (an empty one when absent).
  Object child(const std::string& key);
  /// Array of objects.
  std::vector<Object> children(const std::string& key);
  /// Throws tpf::Error naming the first key that was never read.
  void finish() const;
  /// "file: path.key: message" error.
  [[noreturn]] void fail(const std::string& key, const std::string& message) const;

  const std::string& file() const { return file_; }

  static constexpr double kInfinity = std::numeric_limits<double>::infinity();

 private:
  void check_bound(const std::string& item, double value, Bound bound) const;
  std::string key_path(const std::string& key) const;
  const nlohmann::json& get(const std::string& key);

  nlohmann::json object_;
  std::string file_;
  std::string path_;
  std::set<std::string> used_;
};

/// The key path of the first number in `value` that is NaN or ±∞ ("friction.viscous[2]"), or ""
/// when every number is finite. JSON has no such numbers: nlohmann writes them as null, which the
/// readers then refuse, so the writers check first (require_finite).
template <class Json>
std::string first_non_finite(const Json& value, const std::string& path = "") {
  if (value.is_number_float()) return std::isfinite(value.template get<double>()) ? "" : path;
  if (value.is_array()) {
    for (std::size_t i = 0; i < value.size(); ++i) {
      std::string found = first_non_finite(value[i], path + "[" + std::to_string(i) + "]");
      if (!found.empty()) return found;
    }
  } else if (value.is_object()) {
    for (auto it = value.begin(); it != value.end(); ++it) {
      std::string found =
          first_non_finite(it.value(), path.empty() ? it.key() : path + "." + it.key());
      if (!found.empty()) return found;
    }
  }
  return "";
}

/// Throws tpf::Error "<file>: <key path>: not finite …" when `value` holds a NaN or ±∞, before
/// anything is written: a model fitted on a log with a sample far out of range (1e300 A), or a
/// non-finite option, must not leave a file that looks complete.
template <class Json>
void require_finite(const Json& value, const std::filesystem::path& file) {
  const std::string key = first_non_finite(value);
  if (!key.empty())
    throw Error::at(file.string(), 0, key,
                    "not finite (NaN or ±∞), so nothing was written: an input far out of range "
                    "(a log sample, a file's value or an option) can cause this");
}

}  // namespace tpf::json
