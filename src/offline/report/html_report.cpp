#include "offline/report/html_report.hpp"

#include <algorithm>

#include "offline/report/plot_canvas.hpp"
#include "offline/report/text_format.hpp"
#include "tpf/common/atomic_file.hpp"

namespace tpf::offline {
namespace {

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
  body_ += "<p>" + html_escape(text) + "</p>\n";
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

std::string HtmlReport::html() const {
  std::string page = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
  page += "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n";
  page += "<title>" + html_escape(title_) + "</title>\n<style>" + kStyle + plot_style_sheet() +
          "</style>\n</head>\n";
  page += "<body>\n" + banner_ + "<main>\n<h1>" + html_escape(title_) + "</h1>\n" + body_;
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
