// A tiny well-formedness check for generated HTML/SVG: every tag closed in order, void elements
// and self-closing tags allowed, no stray '<' or '&' in text, <style> content skipped.
#pragma once

#include <cctype>
#include <string>
#include <string_view>
#include <vector>

namespace tpf::offline::test {

/// Empty when `html` is balanced; else a description of the first problem.
inline std::string check_tags(std::string_view html) {
  static const std::vector<std::string_view> kVoid = {"meta", "br", "hr", "img", "link", "input"};
  std::vector<std::string> open;
  std::size_t i = 0;
  while (i < html.size()) {
    const char c = html[i];
    if (c == '&') {
      const std::size_t semi = html.find(';', i);
      if (semi == std::string_view::npos || semi - i > 8) return "bare '&' at " + std::to_string(i);
      i = semi + 1;
      continue;
    }
    if (c == '>') return "bare '>' at " + std::to_string(i);
    if (c != '<') {
      ++i;
      continue;
    }
    const std::size_t close = html.find('>', i);
    if (close == std::string_view::npos) return "unterminated tag at " + std::to_string(i);
    std::string_view tag = html.substr(i + 1, close - i - 1);
    i = close + 1;
    if (tag.empty()) return "empty tag";
    if (tag[0] == '!') continue;  // <!DOCTYPE html>
    const bool closing = tag[0] == '/';
    const bool self_closing = tag.back() == '/';
    if (closing) tag.remove_prefix(1);
    std::size_t end = 0;
    while (end < tag.size() &&
           (std::isalnum(static_cast<unsigned char>(tag[end])) || tag[end] == '-'))
      ++end;
    const std::string name(tag.substr(0, end));
    if (name.empty()) return "bad tag '<" + std::string(tag) + ">'";
    if (closing) {
      if (open.empty() || open.back() != name)
        return "</" + name + "> closes " +
               (open.empty() ? std::string("nothing") : "<" + open.back() + ">");
      open.pop_back();
      continue;
    }
    if (self_closing || std::find(kVoid.begin(), kVoid.end(), name) != kVoid.end()) continue;
    open.push_back(name);
    if (name == "style") {
      const std::size_t style_end = html.find("</style>", i);
      if (style_end == std::string_view::npos) return "unterminated <style>";
      i = style_end;
    }
  }
  if (!open.empty()) return "<" + open.back() + "> never closed";
  return {};
}

}  // namespace tpf::offline::test
