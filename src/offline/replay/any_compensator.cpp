#include "offline/replay/any_compensator.hpp"

#include <string>

#include "tpf/common/error.hpp"
#include "tpf/nn/tcn_weight_file.hpp"

namespace tpf::offline {

void AnyCompensator::resize(int joints) {
  joints_ = joints;
  network_ = None{};
  zero_ = output_ = Output::Zero(joints);
}

void AnyCompensator::load(const CompensatorWeightFiles& weights) {
  const auto per_joint = [&](auto kind, auto network) {
    using Kind = decltype(kind);
    network->resize(joints_);
    Kind::template load<double, Eigen::Dynamic>(*network, weights);
    network_ = std::move(network);
  };
  switch (weights.layout) {
    case CompensatorLayout::None:
      network_ = None{};
      return;
    case CompensatorLayout::AllJoints:
      if (weights.hidden == kAllJointsHidden) {
        auto network = std::make_unique<AllJointsNetwork>();
        network->load(read_tcn_weight_file(weights.files.at(0)), joints_, kAllJointsHidden,
                      kCompensatorLevels, kCompensatorKernel);
        network_ = std::move(network);
        return;
      }
      break;
    case CompensatorLayout::PerJoint:
      if (weights.hidden == kPerJointHiddenSmall)
        return per_joint(PerJointTcn<BFloat16Weights, kPerJointHiddenSmall>{},
                         std::make_unique<SmallPerJoint>());
      if (weights.hidden == kPerJointHiddenLarge)
        return per_joint(PerJointTcn<float, kPerJointHiddenLarge>{},
                         std::make_unique<LargePerJoint>());
      break;
  }
  throw Error::at(weights.source, 0, "architecture.hidden",
                  describe(weights) + ": the tools evaluate one network of " +
                      std::to_string(kAllJointsHidden) + " channels or per-joint networks of " +
                      std::to_string(kPerJointHiddenSmall) + " or " +
                      std::to_string(kPerJointHiddenLarge));
}

int AnyCompensator::receptive_field() const noexcept {
  return std::visit(
      [](const auto& c) {
        using C = std::decay_t<decltype(c)>;
        if constexpr (std::is_same_v<C, None>)
          return 1;
        else
          return compensator_memory_of(*c);
      },
      network_);
}

}  // namespace tpf::offline
