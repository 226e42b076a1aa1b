#include "offline/replay/estimate_columns.hpp"

#include <cmath>
#include <limits>

#include "tpf/common/error.hpp"
#include "tpf/estimation/estimator_status.hpp"

namespace tpf::offline {

namespace {

constexpr int kEstimateTrailingColumns = 6;  // contact, pad, fx, fy, fz, status

/// One recorded cycle: the row of estimate_columns for `out`.
void record_cycle(const EstimatorOutput<double, Eigen::Dynamic>& out, Eigen::MatrixXd& est,
                  Eigen::Index r) {
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  const int n = static_cast<int>(out.external.torque.size());
  const bool present = (out.status & (kStatusNonFiniteInput | kStatusStaleTime)) == 0;
  const auto value = [present](double v) { return present && std::isfinite(v) ? v : nan; };
  for (int j = 0; j < n; ++j)
    est(r, j) = value(out.external.torque[j]);
  const int pad = present ? out.wrench.pad : -1;
  est(r, n) = present ? (out.contact ? 1.0 : 0.0) : nan;
  est(r, n + 1) = present ? static_cast<double>(pad + 1) : nan;
  for (int a = 0; a < 3; ++a)
    est(r, n + 2 + a) = value(pad >= 0 ? out.wrench.force_world[a] : 0.0);
  est(r, n + 5) = static_cast<double>(out.status);
}

}  // namespace

std::vector<std::string> estimate_column_names(int joints) {
  std::vector<std::string> names;
  for (int j = 1; j <= joints; ++j)
    names.push_back(indexed_name("est_tau_ext", j));
  for (const char* name : {"est_contact", "est_pad", "est_fx", "est_fy", "est_fz", "est_status"})
    names.emplace_back(name);
  return names;
}

bool is_estimate_column(const std::string& name) {
  return name.rfind("est_", 0) == 0;
}

Eigen::MatrixXd estimate_columns(ReplayEstimator& estimator,
                                 const std::vector<ReplaySample>& samples) {
  const auto rows = static_cast<Eigen::Index>(samples.size());
  Eigen::MatrixXd est(rows, estimator.joint_count() + kEstimateTrailingColumns);
  estimator.reset();
  for (Eigen::Index r = 0; r < rows; ++r)
    record_cycle(estimator.update(samples[static_cast<std::size_t>(r)]), est, r);
  return est;
}

Log with_estimate_columns(const Log& log, const Eigen::MatrixXd& estimates) {
  if (estimates.rows() != log.rows())
    throw Error::at(log.source, 0, "est_*",
                    std::to_string(estimates.rows()) + " estimated rows for a log of " +
                        std::to_string(log.rows()));
  Log out;
  out.source = log.source;
  out.meta = log.meta;
  out.quality = log.quality;
  out.file_starts = log.file_starts;
  std::vector<Eigen::Index> kept;
  for (std::size_t c = 0; c < log.columns.size(); ++c)
    if (!is_estimate_column(log.columns[c])) {
      kept.push_back(static_cast<Eigen::Index>(c));
      out.columns.push_back(log.columns[c]);
    }
  const auto joints = static_cast<int>(estimates.cols()) - kEstimateTrailingColumns;
  for (const std::string& name : estimate_column_names(joints))
    out.columns.push_back(name);
  out.values.resize(log.rows(), static_cast<Eigen::Index>(out.columns.size()));
  for (std::size_t k = 0; k < kept.size(); ++k)
    out.values.col(static_cast<Eigen::Index>(k)) = log.values.col(kept[k]);
  out.values.rightCols(estimates.cols()) = estimates;
  return out;
}

}  // namespace tpf::offline
