// The frame every SVG plot shares: data → pixel maps, axes with nice ticks, grid, labels, legend.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "offline/report/nice_ticks.hpp"

namespace tpf::offline {

/// What a plot shows around its data. Labels carry units, e.g. "time [s]".
struct PlotOptions {
  std::string title;
  std::string x_label;
  std::string y_label;
  int width = 900;  ///< SVG user units (px); the page column is 920 px wide
  int height = 300;
  bool y_include_zero = false;  ///< extend the y range to 0 (bar charts always do)
};

/// Affine map from a data interval onto a pixel interval: pixel = p0 + (v − d0)·(p1 − p0)/(d1 −
/// d0).
struct AxisMap {
  double data_lo = 0.0, data_hi = 1.0;
  double pixel_lo = 0.0, pixel_hi = 1.0;
  double operator()(double value) const {
    return pixel_lo + (value - data_lo) * (pixel_hi - pixel_lo) / (data_hi - data_lo);
  }
};

/// The CSS that styles every plot (class "plot"): the HTML report embeds it in its page and
/// standalone_svg() in a single SVG file.
const char* plot_style_sheet();

/// Stacks plots (each made with the same width) vertically into one self-contained SVG document,
/// e.g. for a figure in docs/: each plot is `height` units tall.
std::string standalone_svg(const std::vector<std::string>& plots, int width, int height);

/// Colour of series i: a colour-blind-safe palette (Okabe–Ito order, starting with blue).
const char* series_colour(std::size_t i);

/// An SVG plot under construction. The x axis spans the data range exactly (so x_min lands on the
/// left axis); the y axis is widened to nice ticks. Content is clipped to the plot area.
class PlotCanvas {
 public:
  static constexpr double kLeft = 68, kRight = 18, kTop = 44, kBottom = 50;

  /// x and y are data ranges [lo, hi]; NaN or degenerate ranges are widened (see nice_ticks).
  PlotCanvas(PlotOptions options, double x_lo, double x_hi, double y_lo, double y_hi);

  /// Categorical x axis: one label per slot, centred; replaces the numeric x ticks.
  void set_categories(std::vector<std::string> names);
  /// Entries (name, colour) drawn as a legend above the plot area, right-aligned; when they do
  /// not fit in that row, in rows under the x-axis label (the SVG grows by them).
  void set_legend(std::vector<std::pair<std::string, std::string>> entries);
  /// Appends raw SVG elements to the clipped content group.
  void add(const std::string& element) { content_ += element; }

  const AxisMap& x() const { return x_; }
  const AxisMap& y() const { return y_; }
  double plot_left() const { return kLeft; }
  double plot_right() const { return options_.width - kRight; }
  double plot_top() const { return kTop; }
  double plot_bottom() const { return options_.height - kBottom; }

  /// The finished <svg> element.
  std::string svg() const;

 private:
  PlotOptions options_;
  Ticks x_ticks_, y_ticks_;
  AxisMap x_, y_;
  std::vector<std::string> categories_;
  std::vector<std::pair<std::string, std::string>> legend_;
  std::string content_;
};

/// A coordinate with one decimal (enough for screen pixels), for SVG attributes and paths.
std::string svg_coordinate(double pixel);

}  // namespace tpf::offline
