// The documentation's rules (docs_rules.hpp) on planted violations, then on the repository's
// README.md, examples/README.md and docs/.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "docs/docs_rules.hpp"
#include "support/temp_dir.hpp"

namespace {

namespace docs = tpf::test::docs;
using Strings = std::vector<std::string>;

const std::filesystem::path kRoot = std::filesystem::path(TPF_TEST_DATA_DIR).parent_path();

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(DocsRules, CountsLines) {
  EXPECT_EQ(docs::line_count(""), 0u);
  EXPECT_EQ(docs::line_count("a\nb\n"), 2u);
  EXPECT_EQ(docs::line_count("a\nb"), 2u);
  EXPECT_EQ(docs::line_count("\n\n\n"), 3u);
}

TEST(DocsRules, FindsCommitHashes) {
  EXPECT_EQ(docs::commit_hash_tokens("merged in f16a7cc, then (b8920b9)."),
            (Strings{"f16a7cc", "b8920b9"}));
  EXPECT_EQ(docs::commit_hash_tokens("see 7f147da0123456789abcdef0123456789abcdef01"),
            Strings{});  // 41 characters: longer than a hash
  EXPECT_EQ(docs::commit_hash_tokens("ab12cd3"), Strings{"ab12cd3"});
  // Numbers, words and register values are not hashes.
  EXPECT_EQ(docs::commit_hash_tokens("12345678 deadbeef 0x1a2b3c4d a1b2c3 CAFE1234 "
                                     "x1234abcd 1234abcdz cafe_12345 6.259113e-6"),
            Strings{});
}

TEST(DocsRules, FindsHistoryWordsAsWholeWords) {
  EXPECT_EQ(docs::history_words("This Session fixed the issues; in turn, turned, turning."),
            (Strings{"Session", "issues", "turn", "turned", "turning"}));
  EXPECT_EQ(docs::history_words("tissue, return, returns, sessional, issuer, turnover"), Strings{});
}

TEST(DocsRules, CollectsRelativeLinks) {
  const docs::PageLinks links = docs::relative_links(
      "[a](estimator.md) ![shot](img/report.png \"title\") [b](tcn.md#break-away) "
      "[web](https://example.org/x.md) [m](mailto:a@b.c) [anchor](#top) `docs/twin.md` `x.cpp`");
  EXPECT_EQ(links.markdown, (Strings{"estimator.md", "img/report.png", "tcn.md"}));
  EXPECT_EQ(links.quoted, Strings{"docs/twin.md"});
}

TEST(DocsRules, ReportsLinksToMissingFiles) {
  const tpf::test::TempDir dir("docs_links");
  std::filesystem::create_directories(dir / "docs");
  std::ofstream(dir / "docs" / "here.md") << "x\n";
  std::ofstream(dir / "README.md") << "x\n";
  const std::string text =
      "[ok](here.md) [up](../README.md) [gone](missing.md) `docs/here.md` `nowhere.md`";
  EXPECT_EQ(docs::broken_links(dir.path(), "docs/page.md", text),
            (Strings{"missing.md", "nowhere.md"}));
}

TEST(Docs, ReadmeIsShort) {
  EXPECT_LE(docs::line_count(read_text(kRoot / "README.md")), docs::kReadmeMaxLines);
}

TEST(Docs, EveryDocsPageIsShort) {
  const std::vector<std::filesystem::path> pages = docs::documentation_pages(kRoot);
  ASSERT_GT(pages.size(), 5u) << "docs/ holds the pages";
  for (const auto& page : pages) {
    if (page.begin()->string() == "docs") {
      EXPECT_LE(docs::line_count(read_text(kRoot / page)), docs::kDocsPageMaxLines) << page;
    }
  }
}

TEST(Docs, NoCommitHashesOrHistoryWords) {
  for (const auto& page : docs::documentation_pages(kRoot)) {
    const std::string text = read_text(kRoot / page);
    EXPECT_EQ(docs::commit_hash_tokens(text), Strings{}) << page;
    EXPECT_EQ(docs::history_words(text), Strings{}) << page;
  }
}

TEST(Docs, EveryRelativeLinkResolves) {
  for (const auto& page : docs::documentation_pages(kRoot))
    EXPECT_EQ(docs::broken_links(kRoot, page, read_text(kRoot / page)), Strings{}) << page;
}

}  // namespace
