// The rules the documentation keeps (README.md, examples/README.md, docs/): short pages, no
// commit hashes, the product's own words, and every relative link pointing at a file. Each check
// takes a page's text and returns what breaks the rule, so a test can plant a violation.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace tpf::test::docs {

/// The longest README and docs page, in lines.
inline constexpr std::size_t kReadmeMaxLines = 120;
inline constexpr std::size_t kDocsPageMaxLines = 250;

/// Number of lines of `text` (a last line without '\n' counts).
std::size_t line_count(const std::string& text);

/// Tokens that look like a commit hash: 7 to 40 lowercase hex characters, at least one digit and
/// one letter, standing alone (not part of a longer word or a number's decimals, not after "0x").
std::vector<std::string> commit_hash_tokens(const std::string& text);

/// Whole words of the project's history rather than the product: "session", "issue", "turn"
/// (any case, with -s, -ed or -ing). "tissue" or "return" are other words.
std::vector<std::string> history_words(const std::string& text);

/// Relative targets of Markdown links and images `[..](target)` (without "#fragment"; web
/// addresses, mail and in-page anchors left out), and `path.md` in backticks.
struct PageLinks {
  std::vector<std::string> markdown;  ///< relative to the page's folder
  std::vector<std::string> quoted;    ///< `x.md` in backticks: the page's folder or the root
};
PageLinks relative_links(const std::string& text);

/// The links of `page` (under `root`) that name no existing file or folder.
std::vector<std::string> broken_links(const std::filesystem::path& root,
                                      const std::filesystem::path& page, const std::string& text);

/// README.md, examples/README.md and every .md under docs/, relative to `root`.
std::vector<std::filesystem::path> documentation_pages(const std::filesystem::path& root);

}  // namespace tpf::test::docs
