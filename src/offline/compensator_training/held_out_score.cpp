#include "offline/compensator_training/held_out_score.hpp"

#include <cmath>
#include <cstdio>
#include <limits>

#include "tpf/common/error.hpp"
#include "tpf/nn/tcn_weight_file.hpp"

namespace tpf::offline {

HeldOutScore score_held_out(const std::vector<EstimatorTrace>& traces, const RegimeOptions& regimes,
                            int min_rows) {
  if (traces.empty()) throw Error::at("held-out traces", 0, "traces", "no held-out trace");
  const Eigen::Index n = traces.front().residual.cols();
  std::array<Eigen::VectorXd, 3> sum_nominal, sum_compensated;
  HeldOutScore s;
  for (int r = 0; r < 3; ++r) {
    sum_nominal[r] = sum_compensated[r] = Eigen::VectorXd::Zero(n);
    s.rows[r] = Eigen::VectorXi::Zero(n);
  }
  for (const EstimatorTrace& tr : traces) {
    if (tr.residual.cols() != n || tr.compensation.cols() != n || tr.dq.cols() != n)
      throw Error::at("held-out traces", 0, "columns", "joint counts disagree");
    for (Eigen::Index j = 0; j < n; ++j) {
      const Eigen::VectorXd nominal = tr.residual.col(j);
      const Eigen::VectorXd compensated = nominal - tr.compensation.col(j);
      const std::vector<Regime> labels =
          label_regimes(tr.t, tr.dq.col(j), regimes, &nominal, &compensated);
      for (Eigen::Index k = 0; k < tr.rows(); ++k) {
        const Regime regime = labels[static_cast<std::size_t>(k)];
        if (regime == Regime::Invalid || !std::isfinite(nominal[k]) ||
            !std::isfinite(compensated[k]))
          continue;
        const int r = regime_index(regime);  // kHeldOutRegimes' order
        sum_nominal[r][j] += nominal[k] * nominal[k];
        sum_compensated[r][j] += compensated[k] * compensated[k];
        s.rows[r][j] += 1;
      }
    }
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (int r = 0; r < 3; ++r) {
    s.nominal_rmse[r] = s.compensated_rmse[r] = s.gain[r] = Eigen::VectorXd::Constant(n, nan);
    for (Eigen::Index j = 0; j < n; ++j) {
      if (s.rows[r][j] < min_rows) continue;
      s.nominal_rmse[r][j] = std::sqrt(sum_nominal[r][j] / s.rows[r][j]);
      s.compensated_rmse[r][j] = std::sqrt(sum_compensated[r][j] / s.rows[r][j]);
      if (s.nominal_rmse[r][j] > 0)
        s.gain[r][j] = 1.0 - s.compensated_rmse[r][j] / s.nominal_rmse[r][j];
    }
  }
  return s;
}

void set_held_out_gains(CompensatorTraining& training, const HeldOutScore& score) {
  const bool per_joint = training.layout == CompensatorLayout::PerJoint;
  for (std::size_t f = 0; f < training.files.size(); ++f) {
    TcnWeightFile& file = training.files[f];
    for (std::size_t r = 0; r < 3; ++r) {
      file.held_out_gain[r].clear();
      for (int o = 0; o < file.outputs; ++o) {
        const Eigen::Index j = per_joint ? static_cast<Eigen::Index>(f) : o;
        file.held_out_gain[r].push_back(score.gain[r][j]);
      }
    }
  }
}

std::vector<std::string> describe_held_out(const HeldOutScore& score, double min_gain) {
  std::vector<std::string> lines;
  for (Eigen::Index j = 0; j < score.gain[0].size(); ++j) {
    std::string line = "joint " + std::to_string(j + 1) + ":";
    bool kept = true;
    for (std::size_t r = 0; r < 3; ++r) {
      char cell[160];
      const double g = score.gain[r][j];
      if (std::isfinite(g))
        std::snprintf(cell, sizeof cell, " %s %.4g -> %.4g N*m (%+.1f %%, %d rows);",
                      TcnWeightFile::kHeldOutRegimes[r], score.nominal_rmse[r][j],
                      score.compensated_rmse[r][j], -100.0 * g, score.rows[r][j]);
      else
        std::snprintf(cell, sizeof cell, " %s not scored (%d rows);",
                      TcnWeightFile::kHeldOutRegimes[r], score.rows[r][j]);
      line += cell;
      kept = kept && (!std::isfinite(g) || g >= min_gain);
    }
    line += kept ? " the network is used" : " GATED OFF: the estimator uses the nominal residual";
    lines.push_back(line);
  }
  return lines;
}

}  // namespace tpf::offline
