#include "offline/report/line_plot.hpp"

#include <cmath>
#include <limits>

#include "core/common/unoptimised_when_sanitized.hpp"
#include "offline/report/text_format.hpp"
#include "tpf/common/error.hpp"

TPF_UNOPTIMISED_WHEN_SANITIZED_BEGIN

namespace tpf::offline {
namespace {

struct Bounds {
  double x_lo = std::numeric_limits<double>::infinity(), x_hi = -x_lo;
  double y_lo = x_lo, y_hi = -x_lo;
};

Bounds bounds_of(const std::vector<Series>& series) {
  Bounds b;
  for (const Series& s : series) {
    if (s.x.size() != s.y.size())
      throw Error("plot series '" + s.name + "': " + std::to_string(s.x.size()) + " x values for " +
                  std::to_string(s.y.size()) + " y values");
    for (Eigen::Index k = 0; k < s.x.size(); ++k) {
      if (!std::isfinite(s.x[k]) || !std::isfinite(s.y[k])) continue;
      b.x_lo = std::min(b.x_lo, s.x[k]);
      b.x_hi = std::max(b.x_hi, s.x[k]);
      b.y_lo = std::min(b.y_lo, s.y[k]);
      b.y_hi = std::max(b.y_hi, s.y[k]);
    }
  }
  return b;
}

/// SVG path of one series, a new sub-path after each NaN. A series with more samples than twice
/// the plot's pixel columns is decimated to what the pixels show: per column its smallest and
/// largest sample, in time order, at whole pixels, drawn as a point and a vertical stroke
/// ("L x y1 V y2").
std::string path_of(const Series& s, const PlotCanvas& canvas) {
  std::string d;
  bool pen_down = false;
  const auto point = [&](const std::string& px, const std::string& py) {
    d += pen_down ? 'L' : 'M';
    d.append(px).append(" ").append(py);
    pen_down = true;
  };
  const auto pixel = [](double p) { return std::to_string(std::lround(p)); };
  const double columns = canvas.plot_right() - canvas.plot_left();
  const bool decimate = static_cast<double>(s.x.size()) > 2.0 * columns;
  long column = std::numeric_limits<long>::min();
  Eigen::Index lo = -1, hi = -1;  // sample indices of the column's min and max
  const auto flush = [&] {
    if (lo < 0) return;
    const Eigen::Index first = std::min(lo, hi), second = std::max(lo, hi);
    point(std::to_string(column), pixel(canvas.y()(s.y[first])));
    if (second != first) d.append("V").append(pixel(canvas.y()(s.y[second])));
    lo = hi = -1;
  };
  for (Eigen::Index k = 0; k < s.x.size(); ++k) {
    if (!std::isfinite(s.x[k]) || !std::isfinite(s.y[k])) {
      flush();
      pen_down = false;
      continue;
    }
    if (!decimate) {
      point(svg_coordinate(canvas.x()(s.x[k])), svg_coordinate(canvas.y()(s.y[k])));
      continue;
    }
    const long c = std::lround(std::floor(canvas.x()(s.x[k])));
    if (c != column) {
      flush();
      column = c;
    }
    if (lo < 0 || s.y[k] < s.y[lo]) lo = k;
    if (hi < 0 || s.y[k] > s.y[hi]) hi = k;
  }
  flush();
  return d;
}

}  // namespace

std::string line_plot(const PlotOptions& options, const std::vector<Series>& series) {
  const Bounds b = bounds_of(series);
  PlotCanvas canvas(options, b.x_lo, b.x_hi, b.y_lo, b.y_hi);
  std::vector<std::pair<std::string, std::string>> legend;
  for (std::size_t i = 0; i < series.size(); ++i) {
    const std::string colour = series[i].colour.empty() ? series_colour(i) : series[i].colour;
    canvas.add("<path class=\"line\" stroke=\"" + colour + "\" d=\"" + path_of(series[i], canvas) +
               "\"/>\n");
    if (!series[i].name.empty()) legend.emplace_back(series[i].name, colour);
  }
  if (legend.size() > 1 || (legend.size() == 1 && options.title.empty())) canvas.set_legend(legend);
  return canvas.svg();
}

}  // namespace tpf::offline

TPF_UNOPTIMISED_WHEN_SANITIZED_END
