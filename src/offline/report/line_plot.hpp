// Time-series line plots as inline SVG.
#pragma once

#include <string>
#include <vector>

#include "offline/report/plot_canvas.hpp"
#include "offline/report/plot_series.hpp"

namespace tpf::offline {

/// Line plot of several series with a legend. NaN points break the line (gaps stay visible).
/// Series longer than ~2 points per pixel are reduced to the min and max of each pixel column,
/// in sample order, which keeps the envelope (spikes stay visible) and the SVG small.
/// Throws tpf::Error when x and y sizes differ.
std::string line_plot(const PlotOptions& options, const std::vector<Series>& series);

}  // namespace tpf::offline
