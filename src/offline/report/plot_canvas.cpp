#include "offline/report/plot_canvas.hpp"

#include <atomic>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "core/common/unoptimised_when_sanitized.hpp"
#include "offline/report/text_format.hpp"

TPF_UNOPTIMISED_WHEN_SANITIZED_BEGIN

namespace tpf::offline {

const char* plot_style_sheet() {
  return R"(
svg.plot { --ink: #1d2430; --muted: #5b6575; display: block; max-width: 100%; height: auto;
  font-size: 12px; font-family: system-ui, -apple-system, "Segoe UI", Roboto, Arial, sans-serif; }
svg.plot .title { font-size: 14px; font-weight: 600; fill: var(--ink); }
svg.plot .tick-labels text { fill: var(--muted); font-variant-numeric: tabular-nums; }
svg.plot .axis-label { fill: var(--ink); font-size: 12.5px; }
svg.plot .legend text { fill: var(--ink); }
svg.plot .grid line { stroke: #e6e9ee; stroke-width: 1; }
svg.plot .axis { fill: none; stroke: #3a4350; stroke-width: 1.2; }
svg.plot .zero { stroke: #9aa3af; stroke-width: 1; stroke-dasharray: 4 3; }
svg.plot .line { fill: none; stroke-width: 1.4; stroke-linejoin: round; }
svg.plot .dots { fill: none; stroke-width: 4; stroke-linecap: round; stroke-opacity: .45; }
svg.plot .hist { fill-opacity: .28; stroke-width: 1.4; }
svg.plot .bar-value { fill: var(--muted); font-size: 11px; }
)";
}

std::string standalone_svg(const std::vector<std::string>& plots, int width, int height) {
  std::string s = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + std::to_string(width) +
                  "\" height=\"" + std::to_string(height * static_cast<int>(plots.size())) +
                  "\">\n<style>" + plot_style_sheet() +
                  "svg.plot { max-width: none; height: " + std::to_string(height) +
                  "px; }</style>\n<rect width=\"100%\" height=\"100%\" fill=\"#fff\"/>\n";
  for (std::size_t i = 0; i < plots.size(); ++i) {
    // A plot is an <svg> of the given size: place it as a nested viewport.
    std::string plot = plots[i];
    if (plot.rfind("<svg", 0) == 0) {
      plot.insert(4, " y=\"" + std::to_string(height * static_cast<int>(i)) + "\"");
    }
    s += plot + "\n";
  }
  return s + "</svg>\n";
}
namespace {

// `text` in lines of about `width` characters, broken after a space or a hyphen; the last of
// `max_lines` lines takes whatever is left.
std::vector<std::string> wrap_label(const std::string& text, std::size_t width,
                                    std::size_t max_lines) {
  std::vector<std::string> pieces;  // each ends at a break opportunity
  std::string piece;
  for (const char c : text) {
    piece += c;
    if (c == ' ' || c == '-') pieces.push_back(std::move(piece)), piece.clear();
  }
  if (!piece.empty()) pieces.push_back(piece);
  std::vector<std::string> lines{""};
  for (const std::string& p : pieces) {
    if (!lines.back().empty() && utf8_characters(lines.back() + p) > width + 1 &&
        lines.size() < max_lines)
      lines.emplace_back();
    lines.back() += p;
  }
  for (std::string& line : lines)
    while (!line.empty() && line.back() == ' ')
      line.pop_back();
  return lines;
}

std::string tick_label(double value, int decimals, double step) {
  if (std::abs(step) < 1e-4 || std::abs(value) >= 1e6) return format_number(value, 3);
  return format_fixed(value, decimals);
}

/// A document-unique id for the clip path of each plot.
int next_plot_id() {
  static std::atomic<int> counter{0};
  return ++counter;
}

}  // namespace

const char* series_colour(std::size_t i) {
  static constexpr const char* kPalette[] = {"#0072B2", "#D55E00", "#009E73", "#CC79A7",
                                             "#E69F00", "#56B4E9", "#000000", "#F0E442"};
  return kPalette[i % 8];
}

std::string svg_coordinate(double pixel) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.1f", pixel);
  return buffer;
}

PlotCanvas::PlotCanvas(PlotOptions options, double x_lo, double x_hi, double y_lo, double y_hi)
    : options_(std::move(options)) {
  if (options_.y_include_zero && std::isfinite(y_lo) && std::isfinite(y_hi)) {
    y_lo = std::min(y_lo, 0.0);
    y_hi = std::max(y_hi, 0.0);
  }
  x_ticks_ = nice_ticks(x_lo, x_hi, std::max(2, (options_.width - 90) / 90));
  y_ticks_ = nice_ticks(y_lo, y_hi, std::max(2, (options_.height - 90) / 45));
  // x spans the data exactly (ticks inside); degenerate or non-finite x falls back to the ticks.
  const bool x_ok = std::isfinite(x_lo) && std::isfinite(x_hi) && x_hi > x_lo;
  x_ = {x_ok ? x_lo : x_ticks_.lo, x_ok ? x_hi : x_ticks_.hi, plot_left(), plot_right()};
  y_ = {y_ticks_.lo, y_ticks_.hi, plot_bottom(), plot_top()};
}

void PlotCanvas::set_categories(std::vector<std::string> names) {
  categories_ = std::move(names);
  x_ = {0.0, static_cast<double>(std::max<std::size_t>(categories_.size(), 1)), plot_left(),
        plot_right()};
}

void PlotCanvas::set_legend(std::vector<std::pair<std::string, std::string>> entries) {
  legend_ = std::move(entries);
}

std::string PlotCanvas::svg() const {
  // Legend: right-aligned entries above the plot area (≈ 7 px per character) when they fit in one
  // row between the left edge and the plot's right end; else rows under the x-axis label, from
  // the plot's left end, the SVG taller by those rows (an entry never leaves the picture).
  auto entry_width = [](const std::string& name) {
    return 22.0 + 7.0 * static_cast<double>(utf8_characters(name));
  };
  double row_width = 0;
  for (const auto& entry : legend_)
    row_width += entry_width(entry.first) + 10.0;
  const bool legend_above = row_width - 10.0 <= plot_right();
  std::string legend;
  double height = options_.height;
  if (legend_above) {
    double x = plot_right();
    for (auto it = legend_.rbegin(); it != legend_.rend(); ++it) {
      x -= entry_width(it->first);
      legend += "<rect x=\"" + svg_coordinate(x) +
                "\" y=\"26\" width=\"12\" height=\"12\" rx=\"2\" "
                "fill=\"" +
                it->second + "\"/><text x=\"" + svg_coordinate(x + 16) + "\" y=\"36\">" +
                html_escape(it->first) + "</text>";
      x -= 10.0;
    }
  } else {
    double x = plot_left(), y = options_.height + 4.0;
    for (const auto& [name, colour] : legend_) {
      if (x > plot_left() && x + entry_width(name) > plot_right()) {
        x = plot_left();
        y += 20.0;
      }
      legend += "<rect x=\"" + svg_coordinate(x) + "\" y=\"" + svg_coordinate(y) +
                "\" width=\"12\" height=\"12\" rx=\"2\" fill=\"" + colour + "\"/><text x=\"" +
                svg_coordinate(x + 16) + "\" y=\"" + svg_coordinate(y + 10) + "\">" +
                html_escape(name) + "</text>";
      x += entry_width(name) + 10.0;
    }
    height = y + 20.0;
  }
  const std::string w = std::to_string(options_.width);
  const std::string h = legend_above ? std::to_string(options_.height) : svg_coordinate(height);
  const std::string id = "plot" + std::to_string(next_plot_id());
  const std::string left = svg_coordinate(plot_left()), right = svg_coordinate(plot_right());
  const std::string top = svg_coordinate(plot_top()), bottom = svg_coordinate(plot_bottom());
  std::string s;
  s += "<svg xmlns=\"http://www.w3.org/2000/svg\" class=\"plot\" viewBox=\"0 0 " + w + " " + h +
       "\" width=\"" + w + "\" height=\"" + h + "\" role=\"img\" aria-label=\"" +
       html_escape(options_.title) + "\">\n";
  s += "<defs><clipPath id=\"" + id + "\"><rect x=\"" + left + "\" y=\"" + top + "\" width=\"" +
       svg_coordinate(plot_right() - plot_left()) + "\" height=\"" +
       svg_coordinate(plot_bottom() - plot_top()) + "\"/></clipPath></defs>\n";
  if (!options_.title.empty())
    s += "<text class=\"title\" x=\"" + left + "\" y=\"20\">" + html_escape(options_.title) +
         "</text>\n";
  // Grid and y ticks.
  s += "<g class=\"grid\">";
  for (const double v : y_ticks_.values) {
    const std::string py = svg_coordinate(y_(v));
    s += "<line x1=\"" + left + "\" y1=\"" + py + "\" x2=\"" + right + "\" y2=\"" + py + "\"/>";
  }
  s += "</g>\n<g class=\"tick-labels\" text-anchor=\"end\">";
  for (const double v : y_ticks_.values)
    s += "<text x=\"" + svg_coordinate(plot_left() - 8) + "\" y=\"" + svg_coordinate(y_(v) + 4) +
         "\">" + tick_label(v, y_ticks_.decimals, y_ticks_.step) + "</text>";
  s += "</g>\n<g class=\"tick-labels\" text-anchor=\"middle\">";
  const std::string tick_y = svg_coordinate(plot_bottom() + 18);
  if (categories_.empty()) {
    for (const double v : x_ticks_.values) {
      if (v < x_.data_lo - 1e-9 * x_ticks_.step || v > x_.data_hi + 1e-9 * x_ticks_.step) continue;
      s += "<text x=\"" + svg_coordinate(x_(v)) + "\" y=\"" + tick_y + "\">" +
           tick_label(v, x_ticks_.decimals, x_ticks_.step) + "</text>";
    }
  } else {
    // A name wider than its slot (≈ 7 px a character) wraps after a space or a hyphen, onto at
    // most 3 lines (2 when an x-axis label sits below), so neighbours never overlap.
    const double slot = x_(1.0) - x_(0.0);
    const std::size_t width = static_cast<std::size_t>(std::max(4.0, slot / 7.0));
    const std::size_t lines = options_.x_label.empty() ? 3 : 2;
    for (std::size_t i = 0; i < categories_.size(); ++i) {
      const std::string x = svg_coordinate(x_(static_cast<double>(i) + 0.5));
      s += "<text x=\"" + x + "\" y=\"" + tick_y + "\">";
      const std::vector<std::string> wrapped = wrap_label(categories_[i], width, lines);
      for (std::size_t k = 0; k < wrapped.size(); ++k)
        s += (wrapped.size() == 1 ? std::string()
                                  : "<tspan x=\"" + x + "\" dy=\"" + (k ? "13" : "0") + "\">") +
             html_escape(wrapped[k]) + (wrapped.size() == 1 ? "" : "</tspan>");
      s += "</text>";
    }
  }
  s += "</g>\n";
  // Data, clipped to the plot area.
  s += "<g clip-path=\"url(#" + id + ")\">\n" + content_ + "</g>\n";
  // Axes over the data; a zero line when 0 is inside the y range.
  if (y_ticks_.lo < 0 && y_ticks_.hi > 0) {
    const std::string py = svg_coordinate(y_(0.0));
    s += "<line class=\"zero\" x1=\"" + left + "\" y1=\"" + py + "\" x2=\"" + right + "\" y2=\"" +
         py + "\"/>\n";
  }
  s += "<path class=\"axis\" d=\"M" + left + " " + top + "V" + bottom + "H" + right + "\"/>\n";
  if (!options_.x_label.empty())
    s += "<text class=\"axis-label\" text-anchor=\"middle\" x=\"" +
         svg_coordinate(0.5 * (plot_left() + plot_right())) + "\" y=\"" +
         svg_coordinate(options_.height - 10.0) + "\">" + html_escape(options_.x_label) +
         "</text>\n";
  if (!options_.y_label.empty()) {
    const std::string cy = svg_coordinate(0.5 * (plot_top() + plot_bottom()));
    s += "<text class=\"axis-label\" text-anchor=\"middle\" transform=\"translate(16 " + cy +
         ") rotate(-90)\">" + html_escape(options_.y_label) + "</text>\n";
  }
  if (!legend.empty()) s += "<g class=\"legend\">" + legend + "</g>\n";
  s += "</svg>\n";
  return s;
}

}  // namespace tpf::offline

TPF_UNOPTIMISED_WHEN_SANITIZED_END
