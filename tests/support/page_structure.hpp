// What a person takes in from a report page at a glance, checked on its HTML: the page leads with
// a figure or a table, the text outside the collapsed sections comes in short paragraphs, the
// page stays light, and it speaks of itself (no words of the work that made it).
#pragma once

#include <algorithm>
#include <cctype>
#include <string>
#include <string_view>
#include <vector>

namespace tpf::test {

/// A page heavier than this takes long to open and scroll [bytes].
inline constexpr std::size_t kMaxPageBytes = 500 * 1000;
/// The longest paragraph a reader sees without opening a collapsed section [words].
inline constexpr int kMaxParagraphWords = 60;

/// `html` without the collapsed sections (<details> … </details>, nested ones included) and
/// without the <style> sheet: what shows before the reader opens anything.
inline std::string shown_without_opening(std::string_view html) {
  std::string out;
  int depth = 0;
  std::size_t i = 0;
  while (i < html.size()) {
    if (html.compare(i, 8, "<details") == 0) {
      ++depth;
      i += 8;
    } else if (depth > 0 && html.compare(i, 10, "</details>") == 0) {
      --depth;
      i += 10;
    } else if (depth == 0 && html.compare(i, 6, "<style") == 0) {
      const std::size_t end = html.find("</style>", i);
      i = end == std::string_view::npos ? html.size() : end + 8;
    } else {
      if (depth == 0) out += html[i];
      ++i;
    }
  }
  return out;
}

/// The text of `html` without its tags.
inline std::string text_of(std::string_view html) {
  std::string out;
  bool in_tag = false;
  for (const char c : html) {
    if (c == '<') in_tag = true;
    if (!in_tag) out += c;
    if (c == '>') in_tag = false, out += ' ';
  }
  return out;
}

inline int words_in(std::string_view text) {
  int words = 0;
  bool in_word = false;
  for (const char c : text) {
    const bool space = std::isspace(static_cast<unsigned char>(c)) != 0;
    words += !space && !in_word;
    in_word = !space;
  }
  return words;
}

/// The contents of every <name …>…</name> element of `html` (not nested in one another).
inline std::vector<std::string_view> elements(std::string_view html, std::string_view name) {
  std::vector<std::string_view> found;
  // Appended piecewise: GCC 12 -Wrestrict false positive on "<" + name.
  std::string open = "<", close = "</";
  open.append(name);
  close.append(name).append(">");
  for (std::size_t at = html.find(open); at != std::string_view::npos; at = html.find(open, at)) {
    const char after = at + open.size() < html.size() ? html[at + open.size()] : '>';
    if (after != '>' && after != ' ') {  // another element whose name starts alike (<pre>, <path>)
      ++at;
      continue;
    }
    const std::size_t start = html.find('>', at);
    const std::size_t end = html.find(close, start);
    if (start == std::string_view::npos || end == std::string_view::npos) break;
    found.push_back(html.substr(start + 1, end - start - 1));
    at = end + close.size();
  }
  return found;
}

/// Words of the longest paragraph, list item or caption shown before any collapsed section is
/// opened.
inline int longest_shown_paragraph(std::string_view html) {
  const std::string shown = shown_without_opening(html);
  int longest = 0;
  for (const char* name : {"p", "li", "figcaption", "caption"})
    for (const std::string_view block : elements(shown, name))
      longest = std::max(longest, words_in(text_of(block)));
  return longest;
}

/// The first element of the page's content after its title, subtitle and links ("figure",
/// "table", "p", "ul", "pre", "details", …): a page leads with a figure or a table. Section
/// headings and the panels' frames are looked through.
inline std::string leading_element(std::string_view html) {
  const std::size_t title = html.find("</h1>");
  if (title == std::string_view::npos) return "no title";
  for (std::size_t at = html.find('<', title + 5); at != std::string_view::npos;
       at = html.find('<', at + 1)) {
    const std::size_t end = html.find('>', at);
    if (end == std::string_view::npos) break;
    const std::string_view tag = html.substr(at + 1, end - at - 1);
    if (tag.empty() || tag[0] == '/') continue;
    const std::string_view name = tag.substr(0, std::min(tag.find(' '), tag.size()));
    const bool attribute = tag.find("subtitle") != std::string_view::npos ||
                           tag.find("panels") != std::string_view::npos;
    if (name == "h2" || name == "h3" || name == "section" || name == "nav" || name == "a" ||
        (name == "p" && attribute) || (name == "div" && attribute))
      continue;
    if (name == "div" && tag.find("table-scroll") != std::string_view::npos) return "table";
    return std::string(name);
  }
  return "nothing";
}

/// Figures and tables shown before the first collapsed section (<details>).
inline int figures_before_details(std::string_view html) {
  const std::string_view first = html.substr(0, html.find("<details"));
  int count = 0;
  for (const std::string_view element : {"<figure", "<table"})
    for (std::size_t at = first.find(element); at != std::string_view::npos;
         at = first.find(element, at + 1))
      ++count;
  return count;
}

/// The first of the words a page must not use about itself (as a whole word, in any letter
/// case) with its context; empty when there is none.
inline std::string forbidden_word(std::string_view html) {
  static const std::vector<std::string> kForbidden = {"issue",    "issues", "session",
                                                      "sessions", "turn",   "turns"};
  const std::string text = text_of(html);
  std::string word;
  for (std::size_t i = 0; i <= text.size(); ++i) {
    const unsigned char c = i < text.size() ? static_cast<unsigned char>(text[i]) : ' ';
    if (std::isalpha(c)) {
      word += static_cast<char>(std::tolower(c));
      continue;
    }
    if (std::find(kForbidden.begin(), kForbidden.end(), word) != kForbidden.end()) {
      const std::size_t from = i > 60 ? i - 60 : 0;
      return "'" + word + "' in \"…" + text.substr(from, 100) + "…\"";
    }
    word.clear();
  }
  return {};
}

/// Every problem of a report page, one per line; empty when it reads at a glance.
inline std::string page_problems(std::string_view html) {
  std::string problems;
  if (html.size() > kMaxPageBytes)
    problems +=
        std::to_string(html.size()) + " bytes, more than " + std::to_string(kMaxPageBytes) + "\n";
  if (const std::string lead = leading_element(html); lead != "figure" && lead != "table")
    problems += "leads with <" + lead + ">, not with a figure or a table\n";
  if (const int words = longest_shown_paragraph(html); words > kMaxParagraphWords)
    problems += "a paragraph of " + std::to_string(words) + " words shown (at most " +
                std::to_string(kMaxParagraphWords) + ")\n";
  if (const std::string word = forbidden_word(html); !word.empty())
    problems += "speaks of its making: " + word + "\n";
  if (html.find("https://") != std::string_view::npos ||
      html.find("<script") != std::string_view::npos)
    problems += "not self-contained (a script or a network address)\n";
  return problems;
}

}  // namespace tpf::test
