#include "offline/measured_study/low_pass_choice.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "offline/signal/causal_low_pass.hpp"

namespace tpf::offline {
namespace {

/// Sum of squares and count of the finite entries of x in [begin, end).
std::pair<double, double> low_pass_sum_of_squares(const Eigen::VectorXd& x, Eigen::Index begin,
                                                  Eigen::Index end) {
  double sum = 0, n = 0;
  for (Eigen::Index k = begin; k < end; ++k)
    if (std::isfinite(x[k])) sum += x[k] * x[k], ++n;
  return {sum, n};
}

/// Pooled RMSE and the per-file RMSE of x (NaN for a file without finite entries).
double pooled_and_per_file_rms(const Log& log, const Eigen::VectorXd& x,
                               std::vector<double>& per_file) {
  double sum = 0, n = 0;
  per_file.clear();
  for (std::size_t f = 0; f < log.file_count(); ++f) {
    const auto [begin, end] = log.file_rows(f);
    const auto [s, c] = low_pass_sum_of_squares(x, begin, end);
    sum += s, n += c;
    per_file.push_back(c > 0 ? std::sqrt(s / c) : std::numeric_limits<double>::quiet_NaN());
  }
  return n > 0 ? std::sqrt(sum / n) : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace

Eigen::MatrixXd low_passed_residual(const Log& log, const JointSamples& s,
                                    const Eigen::MatrixXd& residual, const Eigen::VectorXd& tau) {
  Eigen::MatrixXd out = residual;
  for (Eigen::Index j = 0; j < std::min<Eigen::Index>(tau.size(), residual.cols()); ++j) {
    if (!(tau[j] > 0)) continue;
    const Eigen::VectorXd effort = s.effort.col(j);
    out.col(j) += causal_low_pass(s.t, effort, tau[j], log.file_starts) - effort;
  }
  return out;
}

LowPassChoice choose_current_low_pass(const Log& log, const JointSamples& s,
                                      const Eigen::MatrixXd& residual, LowPassCriterion criterion,
                                      std::span<const double> candidates) {
  const Eigen::Index joints = residual.cols();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  LowPassChoice out{Eigen::VectorXd::Zero(joints), Eigen::VectorXd::Constant(joints, nan),
                    Eigen::VectorXd::Constant(joints, nan)};
  std::vector<double> raw_files, files;
  for (Eigen::Index j = 0; j < joints; ++j) {
    const Eigen::VectorXd raw = residual.col(j);
    const double raw_rms = pooled_and_per_file_rms(log, raw, raw_files);
    if (!std::isfinite(raw_rms)) continue;
    const Eigen::VectorXd effort = s.effort.col(j);
    out.rmse[j] = raw_rms;
    out.worst_ratio[j] = 1.0;
    for (double tau : candidates) {
      const Eigen::VectorXd x = raw + (causal_low_pass(s.t, effort, tau, log.file_starts) - effort);
      const double pooled = pooled_and_per_file_rms(log, x, files);
      double worst = 0;
      for (std::size_t f = 0; f < files.size(); ++f)
        if (std::isfinite(files[f]) && raw_files[f] > 0)
          worst = std::max(worst, files[f] / raw_files[f]);
      const bool better = criterion == LowPassCriterion::kPooled ? pooled < out.rmse[j]
                                                                 : worst < out.worst_ratio[j];
      if (!better) continue;
      out.time_constant[j] = tau;
      out.rmse[j] = pooled;
      out.worst_ratio[j] = worst;
    }
  }
  return out;
}

}  // namespace tpf::offline
