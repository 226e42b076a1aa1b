#include "offline/identify/identification_setup.hpp"

#include <limits>

#include "offline/identify/parallel_halves.hpp"
#include "tpf/common/error.hpp"
#include "tpf/dynamics/rnea.hpp"

namespace tpf::offline {

template <int N>
IdentificationSetup<N> prepare_identification(const Log& log, const Model<double, N>& model,
                                              const SampleOptions& options) {
  IdentificationSetup<N> setup{
      extract_joint_samples(log, model.torque_constant.template cast<double>(), options),
      {},
      {},
      {}};
  setup.base = rigid_body_base_parameters(model);
  return setup;
}

template <int N>
Eigen::MatrixXd gravity_load(const Model<double, N>& model, const JointSamples& s) {
  Eigen::MatrixXd load(s.size(), N);
  parallel_halves(s.size(), [&](Eigen::Index begin, Eigen::Index end) {
    Data<double, N> data;
    for (Eigen::Index k = begin; k < end; ++k)
      if (s.valid[k])
        load.row(k) = compute_gravity(model, data, s.q.row(k).transpose()).cwiseAbs().transpose();
      else
        load.row(k).setConstant(std::numeric_limits<double>::quiet_NaN());
  });
  return load;
}

#define TPF_INSTANTIATE_SETUP(N)                                                                 \
  template IdentificationSetup<N> prepare_identification<N>(const Log&, const Model<double, N>&, \
                                                            const SampleOptions&);               \
  template Eigen::MatrixXd gravity_load<N>(const Model<double, N>&, const JointSamples&);
TPF_INSTANTIATE_SETUP(1)
TPF_INSTANTIATE_SETUP(2)
TPF_INSTANTIATE_SETUP(3)
TPF_INSTANTIATE_SETUP(4)
TPF_INSTANTIATE_SETUP(5)
TPF_INSTANTIATE_SETUP(6)
TPF_INSTANTIATE_SETUP(7)
#undef TPF_INSTANTIATE_SETUP

}  // namespace tpf::offline
