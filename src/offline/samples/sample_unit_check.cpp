#include "offline/samples/sample_unit_check.hpp"

#include <limits>

#include "tpf/dynamics/rnea.hpp"

namespace tpf::offline {

LogChecks check_sample_units(const ModelX& model, const JointSamples& samples) {
  UnitCheckInput in;
  in.t = samples.t;
  in.q = samples.q;
  in.dq = samples.dq;
  in.ddq = samples.ddq;
  in.effort = samples.effort;
  in.gravity.setConstant(samples.size(), samples.joints(),
                         std::numeric_limits<double>::quiet_NaN());
  DataX data(model);
  Eigen::VectorXd q(model.joint_count());  // sized once, assigned per sample
  for (Eigen::Index r = 0; r < samples.size(); ++r) {
    q = samples.q.row(r).transpose();
    if (q.allFinite()) in.gravity.row(r) = compute_gravity(model, data, q).transpose();
  }
  in.gear_ratio = model.gear_ratio;
  in.torque_constant = model.torque_constant;
  in.effort_is_current = samples.units.unit == EffortUnit::Milliampere;
  in.lower = model.lower;
  in.upper = model.upper;
  for (int j = 0; j < model.joint_count(); ++j)
    in.prismatic.push_back(model.is_prismatic(j));
  return check_log_units(in);
}

}  // namespace tpf::offline
