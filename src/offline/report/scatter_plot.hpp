// Scatter plots (e.g. residual vs explaining variable, before/after) as inline SVG.
#pragma once

#include <string>
#include <vector>

#include "offline/report/plot_canvas.hpp"
#include "offline/report/plot_series.hpp"

namespace tpf::offline {

/// Scatter plot of several series (translucent dots, one colour each, legend), decimated to what
/// the pixels show: one dot per series in each 3 px cell (dots are 4 px across); a series that
/// still has more than `max_points` dots is thinned by a fixed stride (deterministic). Throws
/// tpf::Error when x and y sizes differ.
std::string scatter_plot(const PlotOptions& options, const std::vector<Series>& series,
                         int max_points = 4000);

}  // namespace tpf::offline
