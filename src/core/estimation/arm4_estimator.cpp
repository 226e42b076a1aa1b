// Start-up code of the arm4's estimator: the files loaded, the estimator built behind one call.

#include "tpf/estimation/arm4_estimator.hpp"

#include "tpf/common/error.hpp"
#include "tpf/estimation/estimator_parameter_file.hpp"

namespace tpf {

ArmEstimatorSetup load_arm_estimator_setup(const ArmEstimatorFiles& files) {
  if (files.estimator.empty())
    throw Error::at(files.params, 0, "estimator",
                    "no estimator parameter file given for this model (write one with `tpf "
                    "calibrate` on a contact-free log of the arm)");
  ArmEstimatorSetup setup;
  setup.nominal = load_nominal_model<kArmJoints>(files.params, files.robot);
  setup.pads = load_pads(files.pads, setup.nominal.model);
  setup.parameters = load_estimator_parameters<kArmJoints>(files.estimator);
  if (!files.weights.empty()) setup.weight_files = compensator_files(files.weights, setup.layout);
  return setup;
}

ArmEstimatorStep make_arm_estimator_step(const ArmEstimatorSetup& setup) {
  return with_arm_estimator(setup, [](auto& e) -> ArmEstimatorStep {
    using E = std::decay_t<decltype(e)>;
    auto shared = std::make_shared<E>(std::move(e));
    return [shared](const ArmSample& s) -> const EstimatorOutput<double, kArmJoints>& {
      return shared->update(s);
    };
  });
}

}  // namespace tpf
