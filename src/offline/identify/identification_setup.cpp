#include "offline/identify/identification_setup.hpp"

#include <limits>

#include "offline/fit/parallel_halves.hpp"
#include "tpf/common/error.hpp"
#include "tpf/dynamics/rnea.hpp"

namespace tpf::offline {

IdentificationSetup prepare_identification(const Log& log, const ModelX& model,
                                           const SampleOptions& options) {
  IdentificationSetup setup{extract_joint_samples(log, model.torque_constant, options), {}, {}, {}};
  setup.base = rigid_body_base_parameters(model);
  return setup;
}

Eigen::MatrixXd gravity_load(const ModelX& model, const JointSamples& s) {
  const int joints = model.joint_count();
  Eigen::MatrixXd load(s.size(), joints);
  parallel_halves(s.size(), [&](Eigen::Index begin, Eigen::Index end) {
    DataX data(model);
    Eigen::VectorXd q(joints);  // sized once: assigned per sample
    for (Eigen::Index k = begin; k < end; ++k)
      if (s.valid[k]) {
        for (int j = 0; j < joints; ++j)
          q[j] = s.q(k, j);  // element-wise: no resize path (GCC 12 warns on Eigen's)
        load.row(k) = compute_gravity(model, data, q).cwiseAbs().transpose();
      } else {
        load.row(k).setConstant(std::numeric_limits<double>::quiet_NaN());
      }
  });
  return load;
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
