#include "offline/report/histogram.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/common/unoptimised_when_sanitized.hpp"

TPF_UNOPTIMISED_WHEN_SANITIZED_BEGIN

namespace tpf::offline {

std::vector<std::size_t> bin_counts(const Eigen::VectorXd& samples, double lo, double hi,
                                    int bins) {
  std::vector<std::size_t> counts(static_cast<std::size_t>(std::max(bins, 1)), 0);
  const double width = (hi - lo) / static_cast<double>(counts.size());
  for (const double v : samples) {
    if (!std::isfinite(v) || v < lo || v > hi || !(width > 0)) continue;
    const auto b = std::min(static_cast<std::size_t>((v - lo) / width), counts.size() - 1);
    ++counts[b];
  }
  return counts;
}

std::string histogram(const PlotOptions& options, const std::vector<HistogramSeries>& series,
                      int bins) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const HistogramSeries& s : series)
    for (const double v : s.samples)
      if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
  if (!(hi > lo)) {
    const double centre = std::isfinite(lo) ? lo : 0.0;
    lo = centre - 0.5, hi = centre + 0.5;
  }
  bins = std::max(bins, 1);
  std::vector<std::vector<double>> shares;
  double top = 0.0;
  for (const HistogramSeries& s : series) {
    const auto counts = bin_counts(s.samples, lo, hi, bins);
    std::size_t total = 0;
    for (const auto c : counts)
      total += c;
    std::vector<double> share(counts.size(), 0.0);
    for (std::size_t b = 0; b < counts.size(); ++b)
      share[b] = total ? 100.0 * static_cast<double>(counts[b]) / static_cast<double>(total) : 0.0;
    top = std::max(top, *std::max_element(share.begin(), share.end()));
    shares.push_back(std::move(share));
  }
  PlotOptions with_zero = options;
  with_zero.y_include_zero = true;
  if (with_zero.y_label.empty()) with_zero.y_label = "share of samples [%]";
  PlotCanvas canvas(with_zero, lo, hi, 0.0, top > 0 ? top : 1.0);
  const double width = (hi - lo) / bins;
  std::vector<std::pair<std::string, std::string>> legend;
  for (std::size_t i = 0; i < series.size(); ++i) {
    const std::string colour = series[i].colour.empty() ? series_colour(i) : series[i].colour;
    const std::string base = svg_coordinate(canvas.y()(0.0));
    std::string d = "M" + svg_coordinate(canvas.x()(lo)) + " " + base;
    for (int b = 0; b < bins; ++b) {
      const std::string py = svg_coordinate(canvas.y()(shares[i][static_cast<std::size_t>(b)]));
      d += "V" + py + "H" + svg_coordinate(canvas.x()(lo + width * (b + 1)));
    }
    d += "V" + base + "Z";
    canvas.add("<path class=\"hist\" fill=\"" + colour + "\" stroke=\"" + colour + "\" d=\"" + d +
               "\"/>\n");
    if (!series[i].name.empty()) legend.emplace_back(series[i].name, colour);
  }
  canvas.set_legend(legend);
  return canvas.svg();
}

}  // namespace tpf::offline

TPF_UNOPTIMISED_WHEN_SANITIZED_END
