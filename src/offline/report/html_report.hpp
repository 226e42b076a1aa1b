// A self-contained HTML report: inline CSS and SVG, no scripts, no network.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace tpf::offline {

/// A table of text cells. Cells that read as numbers (digits, sign, '.', 'e', '%', '–') are
/// right-aligned with tabular figures; cells of a percent-change column are coloured green when
/// negative (an error got smaller) and red when positive.
struct Table {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  std::string caption;
  int percent_column = -1;  ///< index of the percent-change column, −1 for none
};

/// A link to another page of a report (relative href), with a line of description.
struct Link {
  std::string href;
  std::string text;
  std::string description;
};

/// Builder of one report page. Text is escaped; SVG from the plot functions is inserted as is.
class HtmlReport {
 public:
  explicit HtmlReport(std::string title);

  /// Shows a "SIMULATED DATA" banner on top: results come from the digital twin, not a robot.
  void mark_simulated(std::string detail = "results from the digital twin, not from a robot");
  /// Shows a "MEASURED DATA" banner: results from logs recorded on a real robot (`detail` names
  /// them and their source).
  void mark_measured(std::string detail);
  /// Shows a banner for a page with both: each section says which it is.
  void mark_mixed(std::string detail = "each section says which");
  /// Subtitle line under the title (e.g. source log and date).
  void subtitle(const std::string& text);
  void heading(const std::string& text, int level = 2);
  /// A paragraph; text of more than 60 words becomes several, cut after sentences.
  void paragraph(const std::string& text);
  /// A bulleted list of text items.
  void list(const std::vector<std::string>& items);
  /// A bulleted list of links (e.g. an index page linking the pages of a report).
  void links(const std::vector<Link>& links);
  /// The links on one line (e.g. the other pages of a report and its JSON files).
  void nav(const std::vector<Link>& links);
  void table(const Table& table);
  /// An SVG plot (from line_plot, scatter_plot, bar_chart, histogram) with an optional caption.
  void figure(const std::string& svg, const std::string& caption = "");
  /// A small monospace block (e.g. a command line or the log quality summary).
  void preformatted(const std::string& text);
  /// Opens a collapsed section titled `summary` (<details>): what follows, up to the matching
  /// close_details(), shows when the reader opens it. Sections nest.
  void open_details(const std::string& summary);
  void close_details();
  /// Panels side by side (wrapping on a narrow screen), each the body() of another HtmlReport
  /// used as a fragment: a first screen of figures and tables. `weights` share the row's width
  /// (empty: equal shares).
  void panels(const std::vector<std::string>& fragments, const std::vector<int>& weights = {});
  /// A page as wide as the screen allows (up to 1360 px) instead of one text column.
  void wide() { wide_ = true; }

  /// What was added so far, without the page around it (for panels()).
  const std::string& body() const { return body_; }

  /// The complete page. Throws tpf::Error when a collapsed section is left open.
  std::string html() const;
  /// Writes the page atomically (temporary + rename). Throws tpf::Error on I/O failure.
  void write(const std::filesystem::path& path) const;

 private:
  std::string title_;
  std::string banner_;
  std::string body_;
  int open_details_ = 0;
  bool wide_ = false;
};

}  // namespace tpf::offline
