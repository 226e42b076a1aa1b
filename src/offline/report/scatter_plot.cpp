#include "offline/report/scatter_plot.hpp"

#include <cmath>
#include <limits>

#include "tpf/common/error.hpp"

namespace tpf::offline {

std::string scatter_plot(const PlotOptions& options, const std::vector<Series>& series,
                         int max_points) {
  double x_lo = std::numeric_limits<double>::infinity(), x_hi = -x_lo, y_lo = x_lo, y_hi = -x_lo;
  std::vector<Eigen::Index> finite_counts;
  for (const Series& s : series) {
    if (s.x.size() != s.y.size())
      throw Error("plot series '" + s.name + "': " + std::to_string(s.x.size()) + " x values for " +
                  std::to_string(s.y.size()) + " y values");
    Eigen::Index count = 0;
    for (Eigen::Index k = 0; k < s.x.size(); ++k) {
      if (!std::isfinite(s.x[k]) || !std::isfinite(s.y[k])) continue;
      ++count;
      x_lo = std::min(x_lo, s.x[k]), x_hi = std::max(x_hi, s.x[k]);
      y_lo = std::min(y_lo, s.y[k]), y_hi = std::max(y_hi, s.y[k]);
    }
    finite_counts.push_back(count);
  }
  PlotCanvas canvas(options, x_lo, x_hi, y_lo, y_hi);
  std::vector<std::pair<std::string, std::string>> legend;
  for (std::size_t i = 0; i < series.size(); ++i) {
    const Series& s = series[i];
    const std::string colour = s.colour.empty() ? series_colour(i) : s.colour;
    const Eigen::Index stride =
        std::max<Eigen::Index>(1, (finite_counts[i] + max_points - 1) / max_points);
    std::string dots = "<g class=\"dots\" fill=\"" + colour + "\">";
    Eigen::Index seen = 0;
    for (Eigen::Index k = 0; k < s.x.size(); ++k) {
      if (!std::isfinite(s.x[k]) || !std::isfinite(s.y[k])) continue;
      if (seen++ % stride != 0) continue;
      dots += "<circle cx=\"" + svg_coordinate(canvas.x()(s.x[k])) + "\" cy=\"" +
              svg_coordinate(canvas.y()(s.y[k])) + "\" r=\"2\"/>";
    }
    canvas.add(dots + "</g>\n");
    if (!s.name.empty()) legend.emplace_back(s.name, colour);
  }
  canvas.set_legend(legend);
  return canvas.svg();
}

}  // namespace tpf::offline
