// The one exception type tpf throws, only from start-up and offline code (never per cycle).
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>

namespace tpf {

/// A user-facing error whose message names where the problem is, e.g.
/// "data/arm4.urdf: joint 'joint3': axis must be a unit vector".
class Error : public std::runtime_error {
 public:
  /// An error without a place: the whole text is the message.
  explicit Error(const std::string& text) : std::runtime_error(text), message_(text) {}
  explicit Error(const char* text) : Error(std::string(text)) {}

  /// "<file>:<line>: <field>: <message>"; line <= 0 and an empty field are left out.
  static Error at(std::string_view file, long line, std::string_view field,
                  std::string_view message) {
    std::string text(file);
    if (line > 0) text.append(":").append(std::to_string(line));
    if (!field.empty()) text.append(": ").append(field);
    text.append(": ").append(message);
    Error error(one_line(std::move(text)));
    error.file_ = one_line(std::string(file));
    error.line_ = line > 0 ? line : 0;
    error.field_ = one_line(std::string(field));
    error.message_ = one_line(std::string(message));
    return error;
  }

  /// The parts of an Error::at (empty / 0 for an error without a place).
  const std::string& file() const noexcept { return file_; }
  long line() const noexcept { return line_; }
  const std::string& field() const noexcept { return field_; }
  const std::string& message() const noexcept { return message_; }

 private:
  /// One line whatever the file quoted back (a name or attribute with a line break in it).
  static std::string one_line(std::string text) {
    for (char& c : text)
      if (c == '\n' || c == '\r') c = ' ';
    return text;
  }

  std::string file_, field_, message_;
  long line_ = 0;
};

}  // namespace tpf
