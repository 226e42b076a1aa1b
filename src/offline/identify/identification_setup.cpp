#include "offline/identify/identification_setup.hpp"

#include <limits>

#include "offline/samples/sample_unit_check.hpp"
#include "tpf/common/error.hpp"

namespace tpf::offline {

IdentificationSetup prepare_identification(const Log& log, const ModelX& model,
                                           const SampleOptions& options) {
  IdentificationSetup setup{
      extract_joint_samples(log, model.torque_constant, options), {}, {}, {}, {}};
  setup.base = rigid_body_base_parameters(model);
  return setup;
}

Eigen::MatrixXd gravity_load(const ModelX& model, const JointSamples& s) {
  return gravity_load(gravity_torque(model, s), s);
}

Eigen::MatrixXd gravity_load(const Eigen::MatrixXd& gravity, const JointSamples& s) {
  Eigen::MatrixXd load(s.size(), gravity.cols());
  for (Eigen::Index k = 0; k < s.size(); ++k)
    if (s.valid[k])
      load.row(k) = gravity.row(k).cwiseAbs();
    else
      load.row(k).setConstant(std::numeric_limits<double>::quiet_NaN());
  return load;
}

}  // namespace tpf::offline
