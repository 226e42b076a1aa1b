// Strict reading of the project's JSON files (robot, pads, friction, parameters, weights,
// scenarios): every key must be known, every number finite and in range; errors name the file and
// the full key path ("joints[2].gear_ratio"). Start-up and offline code only (allocates, throws
// tpf::Error).
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <string_view>
#include <vector>

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
  bool boolean(const std::string& key, bool fallback);
  /// A required string.
  std::string text(const std::string& key);
  std::string text(const std::string& key, std::string fallback);
  /// One of `choices`.
  std::string choice(const std::string& key, std::string fallback,
                     const std::vector<std::string>& choices);
  bool has(const std::string& key) const { return object_.contains(key); }
  /// A nested object (an empty one when absent).
  Object child(const std::string& key);
  /// Array of objects.
  std::vector<Object> children(const std::string& key);
  /// Throws tpf::Error naming the first key that was never read.
  void finish() const;
  /// "file: path.key: message" error.
  [[noreturn]] void fail(const std::string& key, const std::string& message) const;

  const std::string& file() const { return file_; }

 private:
  std::string key_path(const std::string& key) const;
  const nlohmann::json& get(const std::string& key);

  nlohmann::json object_;
  std::string file_;
  std::string path_;
  std::set<std::string> used_;
};

}  // namespace tpf::json
