// Strict reading of one JSON object of a scenario file: every key must be known, every number
// finite and in range; errors name the file and the full key path ("drive.velocity_bandwidth").
#pragma once

#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

namespace tpf::offline {

class StrictObject {
 public:
  /// `path` is the key path of this object inside the file ("" for the top level).
  StrictObject(const nlohmann::json& object, std::string file, std::string path);

  /// A number in [lo, hi]; `fallback` when absent.
  double number(const std::string& key, double fallback, double lo, double hi);
  /// A required number in [lo, hi].
  double number(const std::string& key, double lo, double hi);
  /// An array of exactly `size` numbers in [lo, hi]; `fallback` when absent.
  std::vector<double> numbers(const std::string& key, std::vector<double> fallback, double lo,
                              double hi, std::size_t size);
  bool boolean(const std::string& key, bool fallback);
  std::string text(const std::string& key, std::string fallback);
  /// One of `choices`.
  std::string choice(const std::string& key, std::string fallback,
                     const std::vector<std::string>& choices);
  bool has(const std::string& key) const { return object_.contains(key); }
  /// A nested object (an empty one when absent).
  StrictObject child(const std::string& key);
  /// Array of objects.
  std::vector<StrictObject> children(const std::string& key);
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

}  // namespace tpf::offline
