// The offline tools' friction compensator: the network the weight files hold, chosen at start-up
// (none, one network for all joints, one per joint of 16 or 32 channels), for the arm's joint
// count chosen at start-up too. A controller names its compensator as a type (load_estimator);
// the tools read whatever `tpf train` wrote, so they run one estimator type for every arm and
// dispatch the network per cycle (a few ns offline).
#pragma once

#include <memory>
#include <type_traits>
#include <variant>

#include "offline/replay/all_joints_network.hpp"
#include "tpf/estimation/compensator_types.hpp"

namespace tpf::offline {

/// The compensator kinds the offline tools evaluate (those `tpf train` writes).
inline constexpr int kAllJointsHidden = 32;
/// `tpf train --per-joint` (the default); evaluated as the examples' controllers do, in float with
/// the hidden taps in bfloat16 (PerJointTcn<BFloat16Weights, 16>, docs/tcn.md "Precision").
inline constexpr int kPerJointHiddenSmall = 16;
inline constexpr int kPerJointHiddenLarge = 32;

/// Satisfies FrictionCompensator<AnyCompensator, double, Eigen::Dynamic>; no compensation until
/// load(). The estimator sizes it (resize) before the weights are loaded.
class AnyCompensator {
 public:
  using Input = CompensatorInput<double, Eigen::Dynamic>;
  using Output = Eigen::VectorXd;

  /// Start-up: sizes it for `joints` joints, no network.
  void resize(int joints);
  /// Start-up: the network `weights` hold, loaded for the joint count of resize(). Throws
  /// tpf::Error naming a file of a kind the tools do not evaluate, or of another joint count.
  void load(const CompensatorWeightFiles& weights);

  const Output& step(const Input& x) noexcept {
    return std::visit(
        [&](auto& c) -> const Output& {
          if constexpr (std::is_same_v<std::decay_t<decltype(c)>, None>) {
            return zero_;
          } else {
            output_ = c->step(x);
            return output_;
          }
        },
        network_);
  }
  void reset(const Input& x) noexcept {
    std::visit(
        [&](auto& c) {
          if constexpr (!std::is_same_v<std::decay_t<decltype(c)>, None>) c->reset(x);
        },
        network_);
  }
  /// Cycles of input history the output depends on (the network's receptive field, 1 for none).
  int receptive_field() const noexcept;

 private:
  struct None {};
  using SmallPerJoint =
      PerJointTcn<BFloat16Weights, kPerJointHiddenSmall>::For<double, Eigen::Dynamic>;
  using LargePerJoint = PerJointTcn<float, kPerJointHiddenLarge>::For<double, Eigen::Dynamic>;
  using Networks = std::variant<None, std::unique_ptr<AllJointsNetwork>,
                                std::unique_ptr<SmallPerJoint>, std::unique_ptr<LargePerJoint>>;

  int joints_ = 0;
  Networks network_;
  Output zero_, output_;
};

}  // namespace tpf::offline
