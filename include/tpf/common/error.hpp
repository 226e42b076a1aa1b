// The one exception type tpf throws, only from start-up and offline code (never per cycle).
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>

namespace tpf {

/// A user-facing error whose message names where the problem is, e.g.
/// "data/arm4.urdf: joint 'joint3': axis must be a unit vector".
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;

  /// "<file>:<line>: <field>: <message>"; line <= 0 and an empty field are left out.
  static Error at(std::string_view file, long line, std::string_view field,
                  std::string_view message) {
    std::string text;
    text.reserve(file.size() + field.size() + message.size() + 24);
    text.append(file);
    if (line > 0) text.append(":").append(std::to_string(line));
    if (!field.empty()) text.append(": ").append(field);
    text.append(": ").append(message);
    // One line whatever the file quoted back (a name or attribute with a line break in it).
    for (char& c : text)
      if (c == '\n' || c == '\r') c = ' ';
    return Error(text);
  }
};

}  // namespace tpf
