// Grouped bar charts (e.g. RMSE per regime, before/after, per joint) as inline SVG.
#pragma once

#include <string>
#include <vector>

#include "offline/report/plot_canvas.hpp"
#include "offline/report/plot_series.hpp"

namespace tpf::offline {

/// One slot per group, one bar per series inside it, legend for the series; the y axis includes
/// zero; values are printed above the bars when there are at most 24 bars. NaN bars are left out.
/// Throws tpf::Error when a series does not have one value per group.
std::string bar_chart(const PlotOptions& options, const std::vector<std::string>& groups,
                      const std::vector<BarSeries>& series);

}  // namespace tpf::offline
