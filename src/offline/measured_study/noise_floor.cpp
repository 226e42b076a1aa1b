#include "offline/measured_study/noise_floor.hpp"

#include <algorithm>
#include <cmath>

#include "offline/signal/acceleration.hpp"

namespace tpf::offline {

std::vector<double> high_frequency_rms(const Log& log, const Eigen::VectorXd& t,
                                       const Eigen::MatrixXd& x, double cutoff_hz) {
  Eigen::MatrixXd high = Eigen::MatrixXd::Constant(x.rows(), x.cols(), std::nan(""));
  for (std::size_t f = 0; f < log.file_count(); ++f) {
    const auto [begin, end] = log.file_rows(f);
    const Eigen::Index n = end - begin;
    if (n < 3) continue;
    for (Eigen::Index j = 0; j < x.cols(); ++j) {
      const Eigen::VectorXd part = x.col(j).segment(begin, n);
      high.col(j).segment(begin, n) =
          part - zero_phase_low_pass(t.segment(begin, n), part, cutoff_hz);
    }
  }
  return finite_rms_per_column(high);
}

BandRms band_rms(const Log& log, const Eigen::VectorXd& t, const Eigen::MatrixXd& x, double low_hz,
                 double high_hz) {
  BandRms out;
  out.total = finite_rms_per_column(x);
  const std::vector<double> above_low = high_frequency_rms(log, t, x, low_hz);
  out.high = high_frequency_rms(log, t, x, high_hz);
  const auto rest = [](double a, double b) { return std::sqrt(std::max(0.0, a * a - b * b)); };
  for (std::size_t j = 0; j < out.total.size(); ++j) {
    out.low.push_back(rest(out.total[j], above_low[j]));
    out.mid.push_back(rest(above_low[j], out.high[j]));
  }
  return out;
}

double finite_rms(const Eigen::Ref<const Eigen::VectorXd>& x) {
  double sum = 0, count = 0;
  for (Eigen::Index k = 0; k < x.size(); ++k)
    if (std::isfinite(x[k])) sum += x[k] * x[k], ++count;
  return count > 0 ? std::sqrt(sum / count) : std::nan("");
}

std::vector<double> finite_rms_per_column(const Eigen::MatrixXd& x) {
  std::vector<double> out;
  for (Eigen::Index j = 0; j < x.cols(); ++j)
    out.push_back(finite_rms(x.col(j)));
  return out;
}

}  // namespace tpf::offline
