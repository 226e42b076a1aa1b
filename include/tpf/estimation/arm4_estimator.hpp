// The arm4's estimator assembled at start-up from files: nominal model, pad layout, estimator
// parameter file and compensator weights. The compensator type is chosen by the weight files, so
// the estimator sits behind one call per cycle (ArmEstimatorStep) or a generic visitor
// (with_arm_estimator), which the offline tools use with a recording wrapper.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "tpf/estimation/arm4.hpp"
#include "tpf/estimation/estimator.hpp"
#include "tpf/nn/load_tcn_weights.hpp"
#include "tpf/nn/tcn_weight_file.hpp"
#include "tpf/skin/pad_layout.hpp"

namespace tpf {

/// Everything an arm estimator is built from.
struct ArmEstimatorSetup {
  ArmNominal nominal;
  std::vector<Pad> pads;
  ArmParameters parameters;
  CompensatorLayout layout = CompensatorLayout::None;
  /// One file (AllJoints) or kArmJoints files (PerJoint, joint order).
  std::vector<std::string> weight_files;
};

/// The files of an arm estimator.
struct ArmEstimatorFiles {
  std::string params;     ///< nominal model (tpf-params, `tpf identify` / `tpf diagnose`)
  std::string robot;      ///< robot file the parameters were identified for
  std::string pads;       ///< pad layout (tpf-pads)
  std::string estimator;  ///< estimator parameters (tpf-estimator, `tpf calibrate`)
  /// Compensator weights (compensator_files); empty: no compensator (τ_TCN = 0).
  std::string weights;
};

/// Start-up: loads every file of `files` (core loaders only). Throws tpf::Error naming the file
/// and field on bad input.
ArmEstimatorSetup load_arm_estimator_setup(const ArmEstimatorFiles& files);

/// The compensator itself (no wrapper).
template <typename Compensator>
using PlainCompensator = Compensator;

/// The arm's estimator with compensator `Wrap<Compensator>`.
template <typename Compensator, template <typename> class Wrap = PlainCompensator>
using ArmEstimator = Estimator<double, kArmJoints, kArmPads, Wrap<Compensator>>;

namespace detail {

/// The network inside a (possibly wrapped: member `inner`) compensator.
template <typename C>
auto& unwrapped(C& c) {
  if constexpr (requires { c.inner; })
    return c.inner;
  else
    return c;
}

/// The estimator with per-joint networks of `Hidden` channels loaded from s.weight_files.
template <int Hidden, template <typename> class Wrap>
std::unique_ptr<ArmEstimator<JointTcns<Hidden>, Wrap>> per_joint_arm_estimator(
    const ArmEstimatorSetup& s) {
  auto e = std::make_unique<ArmEstimator<JointTcns<Hidden>, Wrap>>(s.nominal, s.pads, s.parameters);
  for (int j = 0; j < kArmJoints; ++j)
    load_tcn_weights(s.weight_files.at(static_cast<std::size_t>(j)),
                     unwrapped(e->compensator()).network(j));
  return e;
}

}  // namespace detail

/// Start-up: builds the estimator of `setup` on the heap with its compensator (Wrap<…> of the
/// layout's network, weights loaded) and returns use(estimator). Throws tpf::Error naming a bad
/// weight file.
template <template <typename> class Wrap = PlainCompensator, typename Use>
auto with_arm_estimator(const ArmEstimatorSetup& s, Use&& use) {
  switch (s.layout) {
    case CompensatorLayout::AllJoints: {
      auto e = std::make_unique<ArmEstimator<AllJointsTcn, Wrap>>(s.nominal, s.pads, s.parameters);
      load_tcn_weights(s.weight_files.at(0), detail::unwrapped(e->compensator()));
      return use(*e);
    }
    case CompensatorLayout::PerJoint:
      if (read_tcn_weight_file(s.weight_files.at(0)).hidden == kArmHidden)
        return use(*detail::per_joint_arm_estimator<kArmHidden, Wrap>(s));
      return use(*detail::per_joint_arm_estimator<kArmJointHidden, Wrap>(s));
    case CompensatorLayout::None:
      break;
  }
  auto e = std::make_unique<ArmEstimator<ZeroCompensator<double, kArmJoints>, Wrap>>(
      s.nominal, s.pads, s.parameters);
  return use(*e);
}

/// One estimator of `setup`, kept alive inside the returned callable: each call feeds one sample
/// (in time order) and returns the estimator's output (valid until the next call). A call
/// allocates nothing and throws nothing (Estimator::update).
using ArmEstimatorStep =
    std::function<const EstimatorOutput<double, kArmJoints>&(const ArmSample&)>;
ArmEstimatorStep make_arm_estimator_step(const ArmEstimatorSetup& setup);

}  // namespace tpf
