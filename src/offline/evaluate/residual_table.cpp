#include "offline/evaluate/residual_table.hpp"

#include "tpf/common/error.hpp"

namespace tpf::offline {

std::vector<ResidualRow> residual_table(const std::vector<ResidualRecording>& recordings,
                                        const Eigen::VectorXd& meet_tolerance,
                                        const RegimeOptions& options) {
  const Eigen::Index joints = meet_tolerance.size();
  // Per joint (and pooled, index `joints`): the residuals and labels of every recording.
  std::vector<std::vector<double>> nominal(joints + 1), compensated(joints + 1);
  std::vector<std::vector<Regime>> labels(joints + 1);
  for (const ResidualRecording& r : recordings) {
    if (r.dq.cols() != joints || r.nominal.cols() != joints || r.compensated.cols() != joints ||
        r.dq.rows() != r.t.size() || r.nominal.rows() != r.t.size() ||
        r.compensated.rows() != r.t.size())
      throw Error::at("residual table", 0, "recording", "sizes disagree");
    for (Eigen::Index j = 0; j < joints; ++j) {
      const Eigen::VectorXd a = r.nominal.col(j), b = r.compensated.col(j);
      const std::vector<Regime> l =
          label_regimes(r.t, r.dq.col(j), options, &a, &b, meet_tolerance[j]);
      for (Eigen::Index k = 0; k < r.t.size(); ++k) {
        for (const Eigen::Index slot : {j, joints}) {
          nominal[slot].push_back(a[k]);
          compensated[slot].push_back(b[k]);
          labels[slot].push_back(l[static_cast<std::size_t>(k)]);
        }
      }
    }
  }
  std::vector<ResidualRow> rows;
  for (Eigen::Index j = 0; j <= joints; ++j) {
    const auto view = [](const std::vector<double>& v) {
      return Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
    };
    const RegimeStats a = regime_stats(view(nominal[j]), labels[j]);
    const RegimeStats b = regime_stats(view(compensated[j]), labels[j]);
    for (const Regime g : {Regime::Static, Regime::StaticToKinetic, Regime::Moving})
      rows.push_back({j == joints ? -1 : static_cast<int>(j), g, a[g], b[g]});
  }
  return rows;
}

}  // namespace tpf::offline
