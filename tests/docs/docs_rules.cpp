#include "docs_rules.hpp"

#include <algorithm>
#include <cctype>
#include <regex>

namespace tpf::test::docs {
namespace {

bool is_word_char(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
}
bool is_lower_hex(char c) {
  return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f');
}

/// A standalone token at [begin, end) of `text`: no word character on either side.
bool stands_alone(const std::string& text, std::size_t begin, std::size_t end) {
  const bool left = begin == 0 || !is_word_char(text[begin - 1]);
  const bool right = end == text.size() || !is_word_char(text[end]);
  return left && right;
}

bool looks_like_hash(const std::string& token) {
  const bool digit = std::any_of(token.begin(), token.end(), [](char c) { return c <= '9'; });
  const bool letter = std::any_of(token.begin(), token.end(), [](char c) { return c >= 'a'; });
  return token.size() >= 7 && token.size() <= 40 && digit && letter;
}

bool exists_under(const std::filesystem::path& folder, const std::string& target) {
  std::error_code ignored;
  return std::filesystem::exists(folder / target, ignored);
}

}  // namespace

std::size_t line_count(const std::string& text) {
  const auto newlines = static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
  return newlines + (!text.empty() && text.back() != '\n' ? 1 : 0);
}

std::vector<std::string> commit_hash_tokens(const std::string& text) {
  std::vector<std::string> found;
  std::size_t i = 0;
  while (i < text.size()) {
    if (!is_lower_hex(text[i])) {
      ++i;
      continue;
    }
    std::size_t end = i;
    while (end < text.size() && is_lower_hex(text[end]))
      ++end;
    const std::string token = text.substr(i, end - i);
    const bool after_0x = i >= 2 && text.compare(i - 2, 2, "0x") == 0;
    const bool decimals =
        i >= 2 && text[i - 1] == '.' && std::isdigit(static_cast<unsigned char>(text[i - 2]));
    if (stands_alone(text, i, end) && !after_0x && !decimals && looks_like_hash(token))
      found.push_back(token);
    i = end;
    while (i < text.size() && is_word_char(text[i]))
      ++i;  // the rest of a longer word
  }
  return found;
}

std::vector<std::string> history_words(const std::string& text) {
  static const std::regex word(R"(\b(session|issue|turn)(s|ed|ing)?\b)", std::regex::icase);
  std::vector<std::string> found;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), word); it != std::sregex_iterator();
       ++it)
    found.push_back(it->str());
  return found;
}

PageLinks relative_links(const std::string& text) {
  static const std::regex markdown(R"(\]\(\s*<?([^)\s>]+)>?(\s+"[^"]*")?\s*\))");
  static const std::regex quoted(R"(`([A-Za-z0-9_./-]+\.md)`)");
  PageLinks links;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), markdown);
       it != std::sregex_iterator(); ++it) {
    std::string target = (*it)[1].str();
    if (target.find("://") != std::string::npos || target.rfind("mailto:", 0) == 0) continue;
    target = target.substr(0, target.find('#'));
    if (!target.empty()) links.markdown.push_back(target);
  }
  for (auto it = std::sregex_iterator(text.begin(), text.end(), quoted);
       it != std::sregex_iterator(); ++it)
    links.quoted.push_back((*it)[1].str());
  return links;
}

std::vector<std::string> broken_links(const std::filesystem::path& root,
                                      const std::filesystem::path& page, const std::string& text) {
  const std::filesystem::path folder = (root / page).parent_path();
  const PageLinks links = relative_links(text);
  std::vector<std::string> broken;
  for (const std::string& target : links.markdown)
    if (!exists_under(folder, target)) broken.push_back(target);
  for (const std::string& target : links.quoted)
    if (!exists_under(folder, target) && !exists_under(root, target)) broken.push_back(target);
  return broken;
}

std::vector<std::filesystem::path> documentation_pages(const std::filesystem::path& root) {
  std::vector<std::filesystem::path> pages{"README.md", "examples/README.md"};
  for (const auto& entry : std::filesystem::recursive_directory_iterator(root / "docs"))
    if (entry.is_regular_file() && entry.path().extension() == ".md")
      pages.push_back(std::filesystem::relative(entry.path(), root));
  std::sort(pages.begin() + 2, pages.end());
  return pages;
}

}  // namespace tpf::test::docs
