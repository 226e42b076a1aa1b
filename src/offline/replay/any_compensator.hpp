// The offline tools' friction compensator: the network the weight files hold, chosen at start-up
// (none, one network for all joints, one per joint of 16 or 32 channels). A controller names its
// compensator as a type (load_estimator); the tools read whatever `tpf train` wrote, so they run
// one estimator type per joint count and dispatch the network per cycle (a few ns offline).
#pragma once

#include <memory>
#include <string>
#include <variant>

#include "tpf/common/error.hpp"
#include "tpf/estimation/compensator_types.hpp"

namespace tpf::offline {

/// The compensator kinds the offline tools are compiled for (those `tpf train` writes).
inline constexpr int kAllJointsHidden = 32;
/// `tpf train --per-joint` (the default); evaluated as the examples' controllers do, in float with
/// the hidden taps in bfloat16 (PerJointTcn<BFloat16Weights, 16>, docs/tcn.md "Precision").
inline constexpr int kPerJointHiddenSmall = 16;
inline constexpr int kPerJointHiddenLarge = 32;

/// Satisfies FrictionCompensator<AnyCompensator<N>, double, N>; no compensation until load().
template <int N>
class AnyCompensator {
 public:
  using Input = CompensatorInput<double, N>;
  using Output = JointVector<double, N>;

  /// Start-up: the network `weights` hold, loaded. Throws tpf::Error naming a file of a kind the
  /// tools are not compiled for.
  void load(const CompensatorWeightFiles& weights) {
    switch (weights.layout) {
      case CompensatorLayout::None:
        network_ = None{};
        return;
      case CompensatorLayout::AllJoints:
        if (weights.hidden == kAllJointsHidden)
          return emplace<AllJointsTcn<kAllJointsHidden>>(weights);
        break;
      case CompensatorLayout::PerJoint:
        if (weights.hidden == kPerJointHiddenSmall)
          return emplace<PerJointTcn<BFloat16Weights, kPerJointHiddenSmall>>(weights);
        if (weights.hidden == kPerJointHiddenLarge)
          return emplace<PerJointTcn<float, kPerJointHiddenLarge>>(weights);
        break;
    }
    throw Error::at(weights.source, 0, "architecture.hidden",
                    describe(weights) + ": the tools are compiled for one network of " +
                        std::to_string(kAllJointsHidden) + " channels or per-joint networks of " +
                        std::to_string(kPerJointHiddenSmall) + " or " +
                        std::to_string(kPerJointHiddenLarge));
  }

  const Output& step(const Input& x) noexcept {
    return std::visit([&](auto& c) -> const Output& { return step_of(c, x); }, network_);
  }
  void reset(const Input& x) noexcept {
    std::visit([&](auto& c) { reset_of(c, x); }, network_);
  }
  /// Cycles of input history the output depends on (the network's receptive field, 1 for none).
  int receptive_field() const noexcept {
    return std::visit(
        [](const auto& c) {
          using C = std::decay_t<decltype(c)>;
          if constexpr (std::is_same_v<C, None>)
            return 1;
          else
            return compensator_memory<typename C::element_type>;
        },
        network_);
  }

 private:
  struct None {};
  template <typename Kind>
  using Network = std::unique_ptr<typename Kind::template For<double, N>>;
  using Networks = std::variant<None, Network<AllJointsTcn<kAllJointsHidden>>,
                                Network<PerJointTcn<BFloat16Weights, kPerJointHiddenSmall>>,
                                Network<PerJointTcn<float, kPerJointHiddenLarge>>>;

  template <typename Kind>
  void emplace(const CompensatorWeightFiles& weights) {
    auto c = std::make_unique<typename Kind::template For<double, N>>();
    Kind::template load<double, N>(*c, weights);
    network_ = std::move(c);
  }
  const Output& step_of(None&, const Input&) noexcept { return zero_; }
  template <typename C>
  const Output& step_of(std::unique_ptr<C>& c, const Input& x) noexcept {
    output_ = c->step(x);
    return output_;
  }
  void reset_of(None&, const Input&) noexcept {}
  template <typename C>
  void reset_of(std::unique_ptr<C>& c, const Input& x) noexcept {
    c->reset(x);
  }

  Networks network_;
  Output zero_ = Output::Zero();
  Output output_ = Output::Zero();
};

}  // namespace tpf::offline
