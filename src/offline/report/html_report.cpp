#include "offline/report/html_report.hpp"

#include <algorithm>
#include <cctype>
#include <string_view>

#include "core/common/atomic_file.hpp"
#include "core/common/unoptimised_when_sanitized.hpp"
#include "offline/report/plot_canvas.hpp"
#include "offline/report/text_format.hpp"
#include "tpf/common/error.hpp"

TPF_UNOPTIMISED_WHEN_SANITIZED_BEGIN

namespace tpf::offline {
namespace {

/// A paragraph longer than this many words is cut after a sentence (a reader takes in a short
/// one at a glance).
constexpr int kParagraphWords = 60;

constexpr const char* kStyle = R"(
:root { --ink: #1d2430; --muted: #5b6575; --line: #d9dee6; --accent: #0072B2; }
* { box-sizing: border-box; }
body { margin: 0; color: var(--ink); background: #f4f6f9;
  font: 15px/1.55 system-ui, -apple-system, "Segoe UI", Roboto, "Helvetica Neue", Arial, sans-serif; }
main { max-width: 1000px; margin: 0 auto; padding: 28px 40px 56px; background: #fff;
  min-height: 100vh; box-shadow: 0 0 0 1px var(--line); }
.banner { background: repeating-linear-gradient(135deg, #b3261e 0 18px, #c5372e 18px 36px);
  color: #fff; text-align: center; font-weight: 700; letter-spacing: .12em; padding: 8px 12px; }
.banner.measured { background: repeating-linear-gradient(135deg, #005a8c 0 18px, #0b6aa0 18px 36px); }
.banner.mixed { background: repeating-linear-gradient(135deg, #b3261e 0 18px, #005a8c 18px 36px); }
.banner span { font-weight: 400; letter-spacing: normal; opacity: .92; margin-left: .8em; }
h1 { font-size: 26px; margin: 8px 0 2px; letter-spacing: -.01em; }
.subtitle { color: var(--muted); margin: 0 0 18px; }
h2 { font-size: 19px; margin: 32px 0 8px; padding-bottom: 4px; border-bottom: 2px solid var(--line); }
h3 { font-size: 16px; margin: 22px 0 6px; }
p, li { max-width: 78ch; }
table { border-collapse: collapse; margin: 10px 0 6px; font-size: 14px; }
caption { caption-side: top; text-align: left; color: var(--muted); padding-bottom: 4px; }
th, td { padding: 5px 12px; border-bottom: 1px solid var(--line); text-align: left; }
th { background: #eef1f5; font-weight: 600; border-bottom: 2px solid #c9d0da; }
tbody tr:nth-child(even) td { background: #fafbfc; }
td.num, th.num { text-align: right; font-variant-numeric: tabular-nums; }
td.num { white-space: nowrap; }
th { vertical-align: bottom; }
.table-scroll { max-width: 100%; overflow-x: auto; }
td.better { color: #1b7d3a; font-weight: 600; }
td.worse { color: #b3261e; font-weight: 600; }
figure { margin: 16px 0 22px; }
figcaption { color: var(--muted); font-size: 13.5px; margin-top: 2px; max-width: 78ch; }
pre { background: #f4f6f9; border: 1px solid var(--line); border-radius: 4px; padding: 8px 12px;
  font-size: 13px; overflow-x: auto; }
main.wide { max-width: 1360px; padding: 18px 32px 56px; }
main.wide h1 { font-size: 23px; margin-top: 2px; }
main.wide .subtitle { margin-bottom: 10px; }
details { margin: 14px 0; border: 1px solid var(--line); border-radius: 4px; padding: 4px 14px; }
details > summary { cursor: pointer; color: var(--accent); font-weight: 600; padding: 4px 0; }
details[open] > summary { margin-bottom: 6px; }
.panels { display: flex; flex-wrap: wrap; gap: 14px 28px; align-items: flex-start; margin: 4px 0 8px; }
.panel { flex: 1 1 0; min-width: 360px; }
.panel h2 { font-size: 16px; margin: 4px 0 4px; }
.panel table { font-size: 13.5px; margin-top: 2px; }
.panel th, .panel td { padding: 3px 9px; }
.panel figure { margin: 2px 0 4px; }
.panel p { margin: 4px 0; font-size: 13.5px; color: var(--muted); }
nav { margin: 0 0 12px; font-size: 14px; }
footer { margin-top: 40px; color: var(--muted); font-size: 12.5px; border-top: 1px solid var(--line);
  padding-top: 8px; }
)";

bool looks_numeric(const std::string& cell) {
  if (cell.empty()) return false;
  // Digits with sign, decimal point, exponent, percent and the typographic minus/dash/nbsp.
  for (std::size_t i = 0; i < cell.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(cell[i]);
    if ((c >= '0' && c <= '9') || c == '.' || c == '+' || c == '-' || c == 'e' || c == '%' ||
        c == ' ' || c >= 0x80)
      continue;
    return false;
  }
  return true;
}

/// Words of `text` (runs of non-space characters).
int word_count(std::string_view text) {
  int words = 0;
  bool in_word = false;
  for (const char c : text) {
    const bool space = c == ' ' || c == '\n' || c == '\t';
    words += !space && !in_word;
    in_word = !space;
  }
  return words;
}

/// `text` cut after sentences (". " before a capital letter or a digit) into pieces of at most
/// kParagraphWords words each; a longer sentence stays whole.
std::vector<std::string> paragraph_pieces(const std::string& text) {
  std::vector<std::string> sentences;
  std::size_t start = 0;
  for (std::size_t i = 0; i + 2 < text.size(); ++i) {
    const unsigned char next = static_cast<unsigned char>(text[i + 2]);
    if (text[i] == '.' && text[i + 1] == ' ' && (std::isupper(next) || std::isdigit(next))) {
      sentences.push_back(text.substr(start, i + 1 - start));
      start = i + 2;
    }
  }
  sentences.push_back(text.substr(start));
  std::vector<std::string> pieces;
  for (const std::string& sentence : sentences) {
    if (!pieces.empty() && word_count(pieces.back()) + word_count(sentence) <= kParagraphWords)
      pieces.back() += " " + sentence;
    else
      pieces.push_back(sentence);
  }
  return pieces;
}

}  // namespace

HtmlReport::HtmlReport(std::string title) : title_(std::move(title)) {}

void HtmlReport::mark_simulated(std::string detail) {
  banner_ = "<div class=\"banner\" role=\"note\">SIMULATED DATA<span>" + html_escape(detail) +
            "</span></div>\n";
}

void HtmlReport::mark_measured(std::string detail) {
  banner_ = "<div class=\"banner measured\" role=\"note\">MEASURED DATA<span>" +
            html_escape(detail) + "</span></div>\n";
}

void HtmlReport::mark_mixed(std::string detail) {
  banner_ = "<div class=\"banner mixed\" role=\"note\">SIMULATED AND MEASURED DATA<span>" +
            html_escape(detail) + "</span></div>\n";
}

void HtmlReport::subtitle(const std::string& text) {
  body_ += "<p class=\"subtitle\">" + html_escape(text) + "</p>\n";
}

void HtmlReport::heading(const std::string& text, int level) {
  const char digit = static_cast<char>('0' + std::clamp(level, 2, 4));
  body_.append("<h").append(1, digit).append(">").append(html_escape(text));
  body_.append("</h").append(1, digit).append(">\n");
}

void HtmlReport::paragraph(const std::string& text) {
  for (const std::string& piece : paragraph_pieces(text))
    body_ += "<p>" + html_escape(piece) + "</p>\n";
}

void HtmlReport::list(const std::vector<std::string>& items) {
  body_ += "<ul>\n";
  for (const auto& item : items)
    body_ += "<li>" + html_escape(item) + "</li>\n";
  body_ += "</ul>\n";
}

void HtmlReport::links(const std::vector<Link>& links) {
  body_ += "<ul>\n";
  for (const auto& link : links)
    body_ += "<li><a href=\"" + html_escape(link.href) + "\">" + html_escape(link.text) + "</a> " +
             html_escape(link.description) + "</li>\n";
  body_ += "</ul>\n";
}

void HtmlReport::nav(const std::vector<Link>& links) {
  body_ += "<nav>";
  for (std::size_t i = 0; i < links.size(); ++i)
    body_ += std::string(i ? " · " : "") + "<a href=\"" + html_escape(links[i].href) + "\">" +
             html_escape(links[i].text) + "</a>";
  body_ += "</nav>\n";
}

void HtmlReport::table(const Table& table) {
  // Headers wrap; a table still wider than the page scrolls inside it, never past its edge.
  body_ += "<div class=\"table-scroll\"><table>\n";
  if (!table.caption.empty()) body_ += "<caption>" + html_escape(table.caption) + "</caption>\n";
  // A column is numeric when all its non-empty body cells are.
  std::vector<bool> numeric(table.header.size(), true);
  for (const auto& row : table.rows)
    for (std::size_t c = 0; c < row.size() && c < numeric.size(); ++c)
      if (!row[c].empty() && !looks_numeric(row[c])) numeric[c] = false;
  body_ += "<thead><tr>";
  for (std::size_t c = 0; c < table.header.size(); ++c)
    body_ += std::string(numeric[c] && c > 0 ? "<th class=\"num\">" : "<th>") +
             html_escape(table.header[c]) + "</th>";
  body_ += "</tr></thead>\n<tbody>\n";
  for (const auto& row : table.rows) {
    body_ += "<tr>";
    for (std::size_t c = 0; c < row.size(); ++c) {
      std::string cls = (c < numeric.size() && numeric[c] && c > 0) ? "num" : "";
      if (static_cast<int>(c) == table.percent_column && !row[c].empty()) {
        if (row[c].rfind("\u2212", 0) == 0 || row[c][0] == '-')
          cls += " better";
        else if (row[c][0] == '+')
          cls += " worse";
      }
      body_ +=
          (cls.empty() ? "<td>" : "<td class=\"" + cls + "\">") + html_escape(row[c]) + "</td>";
    }
    body_ += "</tr>\n";
  }
  body_ += "</tbody>\n</table></div>\n";
}

void HtmlReport::figure(const std::string& svg, const std::string& caption) {
  body_ += "<figure>\n" + svg;
  if (!caption.empty()) body_ += "<figcaption>" + html_escape(caption) + "</figcaption>\n";
  body_ += "</figure>\n";
}

void HtmlReport::preformatted(const std::string& text) {
  body_ += "<pre>" + html_escape(text) + "</pre>\n";
}

void HtmlReport::open_details(const std::string& summary) {
  body_ += "<details>\n<summary>" + html_escape(summary) + "</summary>\n";
  ++open_details_;
}

void HtmlReport::close_details() {
  if (open_details_ == 0) throw Error("report '" + title_ + "': close_details() with none open");
  body_ += "</details>\n";
  --open_details_;
}

void HtmlReport::panels(const std::vector<std::string>& fragments,
                        const std::vector<int>& weights) {
  body_ += "<div class=\"panels\">\n";
  for (std::size_t i = 0; i < fragments.size(); ++i)
    body_ += "<section class=\"panel\" style=\"flex-grow: " +
             std::to_string(i < weights.size() ? weights[i] : 1) + "\">\n" + fragments[i] +
             "</section>\n";
  body_ += "</div>\n";
}

std::string HtmlReport::html() const {
  if (open_details_ != 0)
    throw Error("report '" + title_ + "': " + std::to_string(open_details_) +
                " collapsed section(s) left open");
  std::string page = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
  page += "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n";
  page += "<title>" + html_escape(title_) + "</title>\n<style>" + kStyle + plot_style_sheet() +
          "</style>\n</head>\n";
  page += "<body>\n" + banner_ + (wide_ ? "<main class=\"wide\">\n<h1>" : "<main>\n<h1>") +
          html_escape(title_) + "</h1>\n" + body_;
  page +=
      "<footer>Generated by tpf. Self-contained page: no scripts, no network access.</footer>\n";
  page += "</main>\n</body>\n</html>\n";
  return page;
}

void HtmlReport::write(const std::filesystem::path& path) const {
  AtomicFile file(path);
  file.write(html());
  file.commit();
}

}  // namespace tpf::offline

TPF_UNOPTIMISED_WHEN_SANITIZED_END
