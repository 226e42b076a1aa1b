#include "tpf/estimation/load_estimator.hpp"

#include "core/common/unoptimised_when_sanitized.hpp"
#include "tpf/common/error.hpp"
#include "tpf/estimation/estimator_parameter_file.hpp"

TPF_UNOPTIMISED_WHEN_SANITIZED_BEGIN

namespace tpf {

EstimatorSetup<Eigen::Dynamic> load_estimator_setup(const EstimatorFiles& files, int joints) {
  if (files.estimator.empty())
    throw Error::at(files.params, 0, "estimator",
                    "no estimator parameter file given for this model (write one with `tpf "
                    "calibrate` on a contact-free log of the arm)");
  EstimatorSetup<Eigen::Dynamic> setup;
  setup.nominal = load_nominal_model(files.params, files.robot, joints);
  const int n = setup.nominal.model.joint_count();
  if (!files.pads.empty()) setup.pads = load_pads(files.pads, setup.nominal.model);
  setup.parameters = load_estimator_parameters(files.estimator, n);
  setup.weights = find_compensator_weights(files.weights, n);
  return setup;
}

}  // namespace tpf

TPF_UNOPTIMISED_WHEN_SANITIZED_END
