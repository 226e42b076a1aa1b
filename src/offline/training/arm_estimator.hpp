// The estimator of the project's 4-joint arm (data/arm4.*) as the offline tools run it: the
// nominal model from a tpf-params file, the pad layout, parameters read off the log's noise, and
// the friction compensator from weight files (one network for all joints, or one per joint).
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "offline/log/log.hpp"
#include "offline/training/estimator_trace.hpp"
#include "tpf/estimation/estimator.hpp"
#include "tpf/estimation/transition_sigma.hpp"
#include "tpf/nn/per_joint_tcn.hpp"
#include "tpf/nn/tcn.hpp"
#include "tpf/skin/pad_layout.hpp"

namespace tpf::offline {

inline constexpr int kArmJoints = 4;
inline constexpr int kArmPads = 11;
using ArmNominal = NominalModel<double, kArmJoints>;
using ArmSample = EstimatorSample<double, kArmJoints, kArmPads>;
using ArmParameters = EstimatorParameters<double, kArmJoints>;
/// Hidden channels and levels of the arm's networks (receptive field 46 samples = 115 ms): one
/// network for all joints has kArmHidden channels; one network per joint has kArmJointHidden (the
/// default, docs/tcn.md "per joint or all joints") or kArmHidden.
inline constexpr int kArmHidden = 32;
inline constexpr int kArmJointHidden = 16;
inline constexpr int kArmLevels = 4;
/// One network for all joints: inputs compensator_input (5N), outputs τ_TCN (N).
using AllJointsTcn =
    Tcn<double, kCompensatorInputsPerJoint * kArmJoints, kArmHidden, kArmLevels, 4, kArmJoints>;
/// One network per joint, Hidden ∈ {kArmJointHidden, kArmHidden}, evaluated in float (trained in
/// double; the float step is ≈ 2× faster, docs/tcn.md "Precision").
template <int Hidden = kArmJointHidden>
using JointTcns = PerJointTcn<double, kArmJoints, Hidden, kArmLevels, float>;
/// Whether the offline tools compile per-joint networks of `hidden` channels.
constexpr bool is_arm_joint_hidden(int hidden) {
  return hidden == kArmJointHidden || hidden == kArmHidden;
}

/// Which compensator the estimator runs.
enum class CompensatorLayout { None, AllJoints, PerJoint };

/// Everything an arm estimator is built from.
struct ArmEstimatorSetup {
  ArmNominal nominal;
  std::vector<Pad> pads;
  ArmParameters parameters;
  CompensatorLayout layout = CompensatorLayout::None;
  /// One file (AllJoints) or kArmJoints files (PerJoint, joint order).
  std::vector<std::string> weight_files;
};

/// Sensor noise the parameters are derived from.
struct SensorNoise {
  JointVector<double, kArmJoints> effort =
      JointVector<double, kArmJoints>::Zero();  ///< effort unit
  double pad_kpa = 0.0;                         ///< raw pad pressure noise [kPa]
};

/// Noise read off a log: per joint, the robust std of the first difference of the effort over
/// consecutive static rows (|q̇_j| < 1e-4 rad/s), divided by √2, σ = 1.4826·MAD(Δe)/√2; the pads'
/// likewise over all rows of every pad column (contacts are rare and slow against the noise).
/// Throws tpf::Error naming the log when a joint never rests.
SensorNoise estimate_sensor_noise(const Log& log);

/// Parameters from the noise: static dead band 3σ·√(1 + 1/5) (static_dead_band_from_noise with
/// the tracker's 12.5 ms = 5-sample window), pad hysteresis levels from the pad noise
/// (detector_settings_from_noise, 12-bit ADC step 0.0105 kPa), pad force gain for
/// `pad_gain_kpa_per_n` on the 25 cm² reference pad. The transition σ stay 0 until calibrated.
ArmParameters arm_estimator_parameters(const SensorNoise& noise, double pad_gain_kpa_per_n = 1.5);

/// The weight files of a compensator path: `path` itself when it holds an all-joints network
/// (inputs 5N, outputs N), else `<path stem>.joint1.json` … `.joint4.json` (per-joint networks
/// of 5 inputs, 1 output, all of the same hidden size, kArmJointHidden or kArmHidden). Throws
/// tpf::Error naming the path when neither exists or a file has the wrong shape.
std::vector<std::string> compensator_files(const std::filesystem::path& path,
                                           CompensatorLayout& layout);

/// Per-joint weight file name of joint j (0-based) for `path`: "<dir>/<stem>.joint<j+1>.json".
std::filesystem::path joint_weight_path(const std::filesystem::path& path, int joint);

/// Runs the estimator of `setup` over `samples` (trace_estimator).
EstimatorTrace trace_arm_estimator(const ArmEstimatorSetup& setup,
                                   const std::vector<ArmSample>& samples);

/// One estimator of `setup`, kept alive inside the returned callable: each call feeds one sample
/// (in time order) and returns the estimator's output (valid until the next call).
using ArmEstimatorStep =
    std::function<const EstimatorOutput<double, kArmJoints>&(const ArmSample&)>;
ArmEstimatorStep make_arm_estimator_step(const ArmEstimatorSetup& setup);

/// The speeds a log covers, per joint: max |q̇_j| over its finite samples [rad/s] (0 when none).
/// Run on the contact-free calibration log it bounds the compensator's domain
/// (EstimatorParameters::compensator_speed_limit): the speeds over which its σ and the torque
/// alarm were calibrated, and, with calibration and training drawn from one scenario, trained.
JointVector<double, kArmJoints> speed_envelope(const std::vector<ArmSample>& samples);

/// calibrate_transition_sigma on contact-free `samples` with the setup's compensator; the result
/// is stored in setup.parameters (nominal_sigma, fused_sigma) and returned.
TransitionSigma<double, kArmJoints> calibrate_arm_sigma(ArmEstimatorSetup& setup,
                                                        const std::vector<ArmSample>& samples,
                                                        const std::string& source);

}  // namespace tpf::offline
