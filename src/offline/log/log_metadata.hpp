// The '# key: value' metadata lines at the top of a tpf log (docs/log-format.md).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace tpf::offline {

/// Metadata of a log, in file order. Unknown keys are kept so that a read → write round trip
/// preserves them. An entry with an empty key is a free comment line ("# text").
struct LogMetadata {
  std::vector<std::pair<std::string, std::string>> entries;

  /// Value of the first entry named `key`, if any.
  std::optional<std::string> get(std::string_view key) const;
  /// Replaces the value of the first entry named `key`, or appends the entry.
  void set(std::string key, std::string value);
  /// Major version from 'tpf-log' ("1", "1.2" → 1); 1 when the key is absent (we write 1).
  /// Throws tpf::Error when the value is not a version number.
  int version() const;
  /// Sample rate from 'rate_hz' in Hz; NaN when absent. Throws tpf::Error when not a positive
  /// number.
  double rate_hz() const;
};

}  // namespace tpf::offline
