#include "offline/signal/acceleration.hpp"

#include "offline/common/not_a_number.hpp"
#include "offline/signal/butterworth.hpp"
#include "offline/signal/segments.hpp"
#include "tpf/common/error.hpp"

namespace tpf::offline {
namespace {

void check_sizes(const Eigen::VectorXd& t, const Eigen::VectorXd& x, const char* what) {
  if (t.size() != x.size())
    throw Error(std::string(what) + ": t has " + std::to_string(t.size()) +
                " samples, the signal " + std::to_string(x.size()));
}

}  // namespace

Eigen::VectorXd zero_phase_low_pass(const Eigen::VectorXd& t, const Eigen::VectorXd& x,
                                    double cutoff_hz) {
  check_sizes(t, x, "zero_phase_low_pass");
  return zero_phase_low_pass(t, x, cutoff_hz, median_step(t));
}

Eigen::VectorXd zero_phase_low_pass(const Eigen::VectorXd& t, const Eigen::VectorXd& x,
                                    double cutoff_hz, double median_step_s) {
  check_sizes(t, x, "zero_phase_low_pass");
  Eigen::VectorXd y = Eigen::VectorXd::Constant(x.size(), kNaN);
  const std::vector<Segment> segments = contiguous_segments(t, x, 1.5, median_step_s);
  if (segments.empty()) return y;
  const double rate = 1.0 / median_step_s;
  const Butterworth2 filter = Butterworth2::low_pass(cutoff_hz, rate);
  for (const Segment& s : segments)
    y.segment(s.begin, s.size()) = filtfilt(filter, x.segment(s.begin, s.size()), rate / cutoff_hz);
  return y;
}

Eigen::VectorXd derive_acceleration(const Eigen::VectorXd& t, const Eigen::VectorXd& dq,
                                    double cutoff_hz) {
  check_sizes(t, dq, "derive_acceleration");
  return derive_acceleration(t, dq, cutoff_hz, median_step(t));
}

Eigen::VectorXd derive_acceleration(const Eigen::VectorXd& t, const Eigen::VectorXd& dq,
                                    double cutoff_hz, double median_step_s) {
  check_sizes(t, dq, "derive_acceleration");
  const Eigen::VectorXd v = zero_phase_low_pass(t, dq, cutoff_hz, median_step_s);
  Eigen::VectorXd ddq = Eigen::VectorXd::Constant(dq.size(), kNaN);
  for (const Segment& s : contiguous_segments(t, dq, 1.5, median_step_s))
    for (Eigen::Index k = s.begin + 1; k + 1 < s.end; ++k)
      ddq[k] = (v[k + 1] - v[k - 1]) / (t[k + 1] - t[k - 1]);
  return ddq;
}

}  // namespace tpf::offline
