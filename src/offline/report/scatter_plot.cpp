#include "offline/report/scatter_plot.hpp"

#include <cmath>
#include <limits>
#include <vector>

#include "core/common/unoptimised_when_sanitized.hpp"
#include "tpf/common/error.hpp"

TPF_UNOPTIMISED_WHEN_SANITIZED_BEGIN

namespace tpf::offline {
namespace {

/// Side of the cells a series keeps one dot of [px]: a dot is 4 px across, so neighbouring cells'
/// dots still touch and a second dot in the same cell changes nothing the reader can tell apart.
constexpr double kCell = 3.0;

/// The dots of one series as one path ("M x y h0" per dot, drawn with round caps): the first
/// finite sample of each occupied cell, at most `max_points` cells (thinned by a fixed stride
/// beyond that, deterministic).
std::string dots_of(const Series& s, const PlotCanvas& canvas, int max_points) {
  const long columns = static_cast<long>(std::ceil(canvas.plot_right() / kCell)) + 2;
  const long rows = static_cast<long>(std::ceil(canvas.plot_bottom() / kCell)) + 2;
  std::vector<bool> taken(static_cast<std::size_t>(columns * rows), false);
  std::vector<std::pair<long, long>> kept;
  for (Eigen::Index k = 0; k < s.x.size(); ++k) {
    if (!std::isfinite(s.x[k]) || !std::isfinite(s.y[k])) continue;
    const double px = canvas.x()(s.x[k]), py = canvas.y()(s.y[k]);
    const long cx = std::lround(std::floor(px / kCell)), cy = std::lround(std::floor(py / kCell));
    if (cx < 0 || cy < 0 || cx >= columns || cy >= rows) continue;
    const auto cell = static_cast<std::size_t>(cy * columns + cx);
    if (taken[cell]) continue;
    taken[cell] = true;
    kept.emplace_back(std::lround(px), std::lround(py));
  }
  const std::size_t stride =
      std::max<std::size_t>(1, (kept.size() + static_cast<std::size_t>(max_points) - 1) /
                                   static_cast<std::size_t>(std::max(max_points, 1)));
  std::string d;
  for (std::size_t i = 0; i < kept.size(); i += stride)
    d.append("M")
        .append(std::to_string(kept[i].first))
        .append(" ")
        .append(std::to_string(kept[i].second))
        .append("h0");  // appended piecewise: GCC 12 -Wrestrict false positive on a + b
  return d;
}

}  // namespace

std::string scatter_plot(const PlotOptions& options, const std::vector<Series>& series,
                         int max_points) {
  double x_lo = std::numeric_limits<double>::infinity(), x_hi = -x_lo, y_lo = x_lo, y_hi = -x_lo;
  for (const Series& s : series) {
    if (s.x.size() != s.y.size())
      throw Error("plot series '" + s.name + "': " + std::to_string(s.x.size()) + " x values for " +
                  std::to_string(s.y.size()) + " y values");
    for (Eigen::Index k = 0; k < s.x.size(); ++k) {
      if (!std::isfinite(s.x[k]) || !std::isfinite(s.y[k])) continue;
      x_lo = std::min(x_lo, s.x[k]), x_hi = std::max(x_hi, s.x[k]);
      y_lo = std::min(y_lo, s.y[k]), y_hi = std::max(y_hi, s.y[k]);
    }
  }
  PlotCanvas canvas(options, x_lo, x_hi, y_lo, y_hi);
  std::vector<std::pair<std::string, std::string>> legend;
  for (std::size_t i = 0; i < series.size(); ++i) {
    const Series& s = series[i];
    const std::string colour = s.colour.empty() ? series_colour(i) : s.colour;
    canvas.add("<path class=\"dots\" stroke=\"" + colour + "\" d=\"" +
               dots_of(s, canvas, max_points) + "\"/>\n");
    if (!s.name.empty()) legend.emplace_back(s.name, colour);
  }
  canvas.set_legend(legend);
  return canvas.svg();
}

}  // namespace tpf::offline

TPF_UNOPTIMISED_WHEN_SANITIZED_END
