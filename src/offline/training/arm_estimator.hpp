// The estimator of the project's 4-joint arm (data/arm4.*) as the offline tools run it: the
// nominal model from a tpf-params file, the pad layout, parameters read off the log's noise, and
// the friction compensator from weight files (one network for all joints, or one per joint).
#pragma once

#include <string>
#include <vector>

#include "offline/log/log.hpp"
#include "offline/training/estimator_trace.hpp"
#include "tpf/estimation/arm4_estimator.hpp"
#include "tpf/estimation/transition_sigma.hpp"

namespace tpf::offline {

// The arm's sizes, networks, weight files and estimator assembly are the core's (shared with the
// run-time loop, examples/arm): tpf/estimation/arm4.hpp, arm4_estimator.hpp.
using tpf::AllJointsTcn;
using tpf::ArmEstimatorSetup;
using tpf::ArmEstimatorStep;
using tpf::ArmNominal;
using tpf::ArmParameters;
using tpf::ArmSample;
using tpf::compensator_files;
using tpf::CompensatorLayout;
using tpf::is_arm_joint_hidden;
using tpf::joint_weight_path;
using tpf::JointTcns;
using tpf::kArmHidden;
using tpf::kArmJointHidden;
using tpf::kArmJoints;
using tpf::kArmLevels;
using tpf::kArmPads;
using tpf::make_arm_estimator_step;

/// Sensor noise the parameters are derived from.
struct SensorNoise {
  JointVector<double, kArmJoints> effort =
      JointVector<double, kArmJoints>::Zero();  ///< effort unit
  double pad_kpa = 0.0;                         ///< raw pad pressure noise [kPa]
};

/// Noise read off a log: per joint, the robust std of the first difference of the effort over
/// consecutive static rows (|q̇_j| < 1e-4 rad/s), divided by √2, σ = 1.4826·MAD(Δe)/√2; the pads'
/// likewise over all pairs of rows of every pad column where both readings are off the sensor's
/// rails (0, full scale: clipped readings repeat and would bias σ low; contacts are rare and slow
/// against the noise).
/// Throws tpf::Error naming the log when a joint never rests.
SensorNoise estimate_sensor_noise(const Log& log);

/// Parameters from the noise: static dead band 3σ·√(1 + 1/5) (static_dead_band_from_noise with
/// the tracker's 12.5 ms = 5-sample window), pad hysteresis levels from the pad noise
/// (detector_settings_from_noise, 12-bit ADC step 0.0105 kPa), pad force gain for
/// `pad_gain_kpa_per_n` on the 25 cm² reference pad. The transition σ stay 0 until calibrated.
ArmParameters arm_estimator_parameters(const SensorNoise& noise, double pad_gain_kpa_per_n = 1.5);

/// Runs the estimator of `setup` over `samples` (trace_estimator).
EstimatorTrace trace_arm_estimator(const ArmEstimatorSetup& setup,
                                   const std::vector<ArmSample>& samples);

/// The speeds a log covers, per joint: max |q̇_j| over its finite samples [rad/s] (0 when none).
/// Run on the contact-free calibration log it bounds the compensator's domain
/// (EstimatorParameters::compensator_speed_limit): the speeds over which its σ and the torque
/// alarm were calibrated, and, with calibration and training drawn from one scenario, trained.
JointVector<double, kArmJoints> speed_envelope(const std::vector<ArmSample>& samples);

/// The accelerations a log covers, per joint: max |q̈_j| over the rows of its trace
/// (trace_arm_estimator) as the estimator computed it — the compensator's q̈ input: the sample's,
/// or the filtered derivative of q̇ [rad/s²]. On the contact-free calibration log it bounds the
/// compensator's domain with speed_envelope (EstimatorParameters::compensator_acceleration_limit).
JointVector<double, kArmJoints> acceleration_envelope(const EstimatorTrace& tr);

/// calibrate_transition_sigma on contact-free `samples` with the setup's compensator; the result
/// is stored in setup.parameters (nominal_sigma, fused_sigma) and returned.
TransitionSigma<double, kArmJoints> calibrate_arm_sigma(ArmEstimatorSetup& setup,
                                                        const std::vector<ArmSample>& samples,
                                                        const std::string& source);

}  // namespace tpf::offline
