#include "offline/samples/sample_unit_check.hpp"

#include <limits>

#include "offline/fit/parallel_halves.hpp"
#include "tpf/dynamics/rnea.hpp"

namespace tpf::offline {

Eigen::MatrixXd gravity_torque(const ModelX& model, const JointSamples& samples) {
  const int joints = model.joint_count();
  Eigen::MatrixXd gravity(samples.size(), joints);
  parallel_halves(samples.size(), [&](Eigen::Index begin, Eigen::Index end) {
    DataX data(model);
    Eigen::VectorXd q(joints);  // sized once: assigned per sample
    for (Eigen::Index k = begin; k < end; ++k) {
      for (int j = 0; j < joints; ++j)
        q[j] = samples.q(k, j);  // element-wise: no resize path (GCC 12 warns on Eigen's)
      if (q.allFinite())
        gravity.row(k) = compute_gravity(model, data, q).transpose();
      else
        gravity.row(k).setConstant(std::numeric_limits<double>::quiet_NaN());
    }
  });
  return gravity;
}

LogChecks check_sample_units(const ModelX& model, const JointSamples& samples,
                             const Eigen::MatrixXd& gravity) {
  const Eigen::MatrixXd computed =
      gravity.size() == 0 ? gravity_torque(model, samples) : Eigen::MatrixXd();
  std::vector<bool> prismatic;
  for (int j = 0; j < model.joint_count(); ++j)
    prismatic.push_back(model.is_prismatic(j));
  return check_log_units(UnitCheckView{
      samples.t, samples.q, samples.dq, samples.ddq, samples.effort,
      gravity.size() == 0 ? computed : gravity, model.gear_ratio, model.torque_constant,
      samples.units.unit == EffortUnit::Milliampere, model.lower, model.upper, prismatic});
}

}  // namespace tpf::offline
