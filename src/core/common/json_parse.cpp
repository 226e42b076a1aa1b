#include "core/common/json_parse.hpp"

#include <algorithm>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "core/common/unoptimised_when_sanitized.hpp"
#include "tpf/common/error.hpp"

TPF_UNOPTIMISED_WHEN_SANITIZED_BEGIN

namespace tpf::json {
namespace {

constexpr int kMaxDepth = 64;

/// The whole file as text (for locating an error after the parser gave up).
std::string file_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// 1 + the number of line breaks before the 1-based offset `byte`.
long line_of(const std::string& text, std::size_t byte) {
  const auto end = text.begin() + static_cast<std::ptrdiff_t>(std::min(byte - 1, text.size()));
  return 1 + std::count(text.begin(), end, '\n');
}

/// "file:line: not valid JSON: <what>". `byte` is parse_error::byte, or 0 for other parse
/// exceptions (out_of_range 406: a number too large for a double), whose line is that of the
/// token `what` quotes.
[[noreturn]] void fail_unparsable(const std::filesystem::path& path, std::size_t byte,
                                  std::string_view what) {
  const std::string text = file_text(path);
  if (byte == 0) {
    const std::size_t open = what.find('\'');
    const std::size_t close = open == std::string_view::npos ? open : what.find('\'', open + 1);
    if (close != std::string_view::npos) {
      const std::size_t at = text.find(what.substr(open + 1, close - open - 1));
      if (at != std::string::npos) byte = at + 1;
    }
  }
  throw Error::at(path.string(), byte == 0 ? 0 : line_of(text, byte), "",
                  std::string("not valid JSON: ").append(what));
}

/// "file:line: nested deeper than 64 levels", the line where level 65 opens.
[[noreturn]] void fail_too_deep(const std::filesystem::path& path) {
  const std::string text = file_text(path);
  int depth = 0;
  bool in_string = false, escaped = false;
  std::size_t at = 0;
  for (; at < text.size() && depth <= kMaxDepth; ++at) {
    const char c = text[at];
    if (in_string) {
      if (c == '"' && !escaped) in_string = false;
      escaped = !escaped && c == '\\';
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      ++depth;
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  throw Error::at(path.string(), line_of(text, at), "",
                  "nested deeper than " + std::to_string(kMaxDepth) + " levels");
}

}  // namespace

nlohmann::json parse_file(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw Error::at(path.string(), 0, "", "cannot open the file");
  // Copying, printing or comparing a json value recurses once per level: bound the nesting.
  const auto bounded_depth = [&](int depth, nlohmann::json::parse_event_t, nlohmann::json&) {
    if (depth > kMaxDepth) fail_too_deep(path);
    return true;
  };
  try {
    return nlohmann::json::parse(in, bounded_depth);
  } catch (const nlohmann::json::parse_error& e) {
    fail_unparsable(path, e.byte, e.what());
  } catch (const nlohmann::json::exception& e) {  // e.g. a number too large for a double
    fail_unparsable(path, 0, e.what());
  }
}

}  // namespace tpf::json

TPF_UNOPTIMISED_WHEN_SANITIZED_END
