#include "tpf/estimation/load_estimator.hpp"

#include "tpf/common/error.hpp"
#include "tpf/common/joint_counts.hpp"
#include "tpf/estimation/estimator_parameter_file.hpp"

namespace tpf {

template <int N>
EstimatorSetup<N> load_estimator_setup(const EstimatorFiles& files) {
  if (files.estimator.empty())
    throw Error::at(files.params, 0, "estimator",
                    "no estimator parameter file given for this model (write one with `tpf "
                    "calibrate` on a contact-free log of the arm)");
  EstimatorSetup<N> setup;
  setup.nominal = load_nominal_model<N>(files.params, files.robot);
  if (!files.pads.empty()) setup.pads = load_pads(files.pads, setup.nominal.model);
  setup.parameters = load_estimator_parameters<N>(files.estimator);
  setup.weights = find_compensator_weights(files.weights, N);
  return setup;
}

#define TPF_INSTANTIATE_LOAD_ESTIMATOR_SETUP(N) \
  template EstimatorSetup<N> load_estimator_setup<N>(const EstimatorFiles&);
TPF_FOR_EACH_JOINT_COUNT(TPF_INSTANTIATE_LOAD_ESTIMATOR_SETUP)
#undef TPF_INSTANTIATE_LOAD_ESTIMATOR_SETUP

}  // namespace tpf
