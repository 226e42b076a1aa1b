// The page-structure checker (tests/support/page_structure.hpp) and the report kit's parts that
// keep a page readable at a glance: collapsed sections, panels, paragraphs cut after sentences.
#include "support/page_structure.hpp"

#include <gtest/gtest.h>

#include "offline/report/html_report.hpp"
#include "offline/report/line_plot.hpp"
#include "tag_checker.hpp"
#include "tpf/common/error.hpp"

namespace tpf::offline {
namespace {

/// `n` words: "w1 w2 … wn".
std::string words(int n, const std::string& stem = "w") {
  std::string text;
  for (int i = 1; i <= n; ++i)
    text += (i > 1 ? " " : "") + stem + std::to_string(i);
  return text;
}

Table small_table() {
  Table t;
  t.header = {"joint", "RMSE"};
  t.rows = {{"1", "2.5"}, {"2", "3.1"}};
  return t;
}

TEST(PageStructure, ALongParagraphIsCutAfterSentencesAndKeepsEveryWord) {
  // Three sentences of 25 words: the first two make one paragraph (50 words), the third another.
  const std::string sentence = words(24, "Word") + " end.";
  HtmlReport page("cut");
  page.paragraph(sentence + " " + sentence + " " + sentence);
  const std::string html = page.html();
  const auto paragraphs = tpf::test::elements(html, "p");
  ASSERT_EQ(paragraphs.size(), 2u);
  EXPECT_EQ(tpf::test::words_in(paragraphs[0]), 50);
  EXPECT_EQ(tpf::test::words_in(paragraphs[1]), 25);
  // A sentence that is longer than the limit alone stays whole; a decimal point is no cut.
  HtmlReport one("whole");
  one.paragraph(words(70) + " 3.5 N·m.");
  EXPECT_EQ(tpf::test::elements(one.html(), "p").size(), 1u);
  EXPECT_EQ(tpf::test::longest_shown_paragraph(one.html()), 72);
}

TEST(PageStructure, CollapsedSectionsNestAndMustBeClosed) {
  HtmlReport page("details");
  page.table(small_table());
  page.open_details("outer");
  page.paragraph(words(80));
  page.open_details("inner <b>");
  page.paragraph("inside");
  page.close_details();
  page.close_details();
  const std::string html = page.html();
  EXPECT_EQ(test::check_tags(html), "");
  EXPECT_NE(html.find("<summary>inner &lt;b&gt;</summary>"), std::string::npos);
  // The 80 words are hidden until the reader opens the section.
  EXPECT_EQ(tpf::test::longest_shown_paragraph(html), 0);
  EXPECT_EQ(tpf::test::shown_without_opening(html).find("inside"), std::string::npos);
  EXPECT_EQ(tpf::test::page_problems(html), "");
  HtmlReport open("open");
  open.open_details("never closed");
  EXPECT_THROW(open.html(), Error);
  EXPECT_THROW(HtmlReport("x").close_details(), Error);
}

TEST(PageStructure, PanelsShareTheFirstScreen) {
  HtmlReport left(""), right("");
  left.heading("Table");
  left.table(small_table());
  right.heading("Figure");
  right.figure(
      line_plot({"", "t [s]", "y"}, {{"y", Eigen::Vector2d(0, 1), Eigen::Vector2d(1, 2), ""}}));
  HtmlReport page("panels");
  page.wide();
  page.subtitle("one line");
  page.nav({{"a.html", "a", ""}, {"b.json", "b", ""}});
  page.panels({left.body(), right.body()}, {2, 3});
  page.open_details("more");
  page.table(small_table());
  page.close_details();
  const std::string html = page.html();
  EXPECT_EQ(test::check_tags(html), "");
  EXPECT_NE(html.find("<main class=\"wide\">"), std::string::npos);
  EXPECT_NE(html.find("style=\"flex-grow: 3\""), std::string::npos);
  EXPECT_EQ(tpf::test::leading_element(html), "table");
  EXPECT_EQ(tpf::test::figures_before_details(html), 2);
  EXPECT_EQ(tpf::test::page_problems(html), "");
}

TEST(PageStructure, TheCheckerFindsWhatAReaderWouldMiss) {
  HtmlReport prose("prose first");
  prose.paragraph("Some words before the figure.");
  prose.table(small_table());
  EXPECT_EQ(tpf::test::leading_element(prose.html()), "p");
  EXPECT_NE(tpf::test::page_problems(prose.html()).find("leads with <p>"), std::string::npos);

  HtmlReport list("long list item");
  list.table(small_table());
  list.list({words(61)});
  EXPECT_NE(tpf::test::page_problems(list.html()).find("a paragraph of 61 words"),
            std::string::npos);

  HtmlReport words_of_making("words");
  words_of_making.table(small_table());
  words_of_making.open_details("hidden text counts too");
  words_of_making.paragraph("As the Issue's goal says.");
  words_of_making.close_details();
  EXPECT_NE(tpf::test::page_problems(words_of_making.html()).find("'issue'"), std::string::npos);
  HtmlReport fine("words that only contain them");
  fine.table(small_table());
  fine.paragraph("Return the turnover of the tissues; sessional.");
  EXPECT_EQ(tpf::test::forbidden_word(fine.html()), "");

  HtmlReport heavy("heavy");
  heavy.table(small_table());
  heavy.preformatted(std::string(tpf::test::kMaxPageBytes, 'x'));
  EXPECT_NE(tpf::test::page_problems(heavy.html()).find("bytes, more than 500000"),
            std::string::npos);
}

}  // namespace
}  // namespace tpf::offline
