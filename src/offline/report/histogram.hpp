// Histograms of error distributions (overlaid, e.g. before/after) as inline SVG.
#pragma once

#include <string>
#include <vector>

#include "offline/report/plot_canvas.hpp"
#include "offline/report/plot_series.hpp"

namespace tpf::offline {

/// Overlaid histograms on common bins spanning all finite samples; y is the share of each
/// series' finite samples per bin in percent, so sets of different size compare. Drawn as
/// translucent filled steps with a solid outline.
std::string histogram(const PlotOptions& options, const std::vector<HistogramSeries>& series,
                      int bins = 40);

/// Counts of the finite `samples` in `bins` equal bins over [lo, hi] (hi inclusive; outside
/// values ignored).
std::vector<std::size_t> bin_counts(const Eigen::VectorXd& samples, double lo, double hi, int bins);

}  // namespace tpf::offline
