// Data handed to the SVG plots.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

namespace tpf::offline {

/// One named (x, y) series for line and scatter plots. NaN points are skipped (and break lines).
/// An empty colour takes the palette colour of the series' position.
struct Series {
  std::string name;
  Eigen::VectorXd x;
  Eigen::VectorXd y;
  std::string colour;
};

/// One named series of a grouped bar chart: one value per group.
struct BarSeries {
  std::string name;
  std::vector<double> values;
  std::string colour;
};

/// One named sample set of a histogram (NaN skipped).
struct HistogramSeries {
  std::string name;
  Eigen::VectorXd samples;
  std::string colour;
};

}  // namespace tpf::offline
