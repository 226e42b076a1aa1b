// The run-time estimator as the offline tools replay it over a log, for any arm: the joint count
// of its nominal model, the pad count of the layout (0: no skin), and the compensator the weight
// files hold (none, one network for all joints, or one per joint) — the same core Estimator a
// controller builds with load_estimator, with its sizes chosen at start-up (Eigen::Dynamic).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "offline/log/log.hpp"
#include "offline/replay/any_compensator.hpp"
#include "offline/replay/estimator_samples.hpp"
#include "offline/replay/estimator_trace.hpp"
#include "offline/replay/recording_compensator.hpp"
#include "tpf/common/error.hpp"
#include "tpf/estimation/estimator.hpp"
#include "tpf/estimation/load_estimator.hpp"
#include "tpf/estimation/transition_sigma.hpp"

namespace tpf::offline {

/// What the tools build an estimator from: nominal model, pads, parameters and compensator
/// weights of any arm (joint count at run time).
using ReplaySetup = EstimatorSetup<Eigen::Dynamic>;
/// Estimator parameters of any arm.
using ReplayParameters = EstimatorParameters<double, Eigen::Dynamic>;
/// A per-joint vector of any arm.
using ReplayVector = JointVector<double, Eigen::Dynamic>;

/// The estimator the offline tools replay: the setup's joints and pads (any counts), the
/// compensator the weight files hold (AnyCompensator), recording the input it was given.
using ReplayEstimator = Estimator<double, Eigen::Dynamic, Eigen::Dynamic,
                                  RecordingCompensator<AnyCompensator, double, Eigen::Dynamic>>;

/// Start-up: the estimator of `setup` on the heap, its compensator's weights loaded and the
/// held-out gate applied. Throws tpf::Error naming a weight file of a kind the tools do not
/// evaluate.
std::unique_ptr<ReplayEstimator> make_replay_estimator(const ReplaySetup& setup);

/// Runs `estimator` (reset first) over `samples` in order and records every row (EstimatorTrace).
EstimatorTrace trace_estimator(ReplayEstimator& estimator,
                               const std::vector<ReplaySample>& samples);

/// The replay estimator of a setup driven one sample at a time, for closed loops whose next
/// sample depends on the estimate (closed_loop_teaching).
class SteppedEstimator {
 public:
  /// Start-up: as make_replay_estimator.
  explicit SteppedEstimator(const ReplaySetup& setup);
  ~SteppedEstimator();
  SteppedEstimator(const SteppedEstimator&) = delete;
  SteppedEstimator& operator=(const SteppedEstimator&) = delete;

  const EstimatorOutput<double, Eigen::Dynamic>& update(const ReplaySample& sample) noexcept;

 private:
  std::unique_ptr<ReplayEstimator> estimator_;
};

/// Sensor noise the parameters are derived from.
struct SensorNoise {
  Eigen::VectorXd effort;       ///< per joint [N·m]
  Eigen::VectorXd effort_step;  ///< per joint: the log's effort resolution, 1 unit (1 mA) [N·m]
  double pad_kpa = 0.0;         ///< raw pad pressure noise [kPa]
};

/// Noise read off a log: per joint, the robust std of the first difference of the effort over
/// consecutive static rows (|q̇_j| < 1e-4 rad/s), divided by √2, σ = 1.4826·MAD(Δe)/√2, in N·m
/// (a log in mA converted with `torque_constant`, the robot file's K_t per joint); the pads'
/// likewise over all pairs of rows of every pad column where both readings are off the sensor's
/// rails (0, full scale: clipped readings repeat and would bias σ low; contacts are rare and slow
/// against the noise); 0 without pads.
/// Throws tpf::Error naming the log when a joint never rests, unless `never_rests` is given: it
/// then gets those joints (0-based), whose noise is taken as the largest of the joints that rest
/// (their static estimate, which needs rest, is never used; 0 when no joint rests).
SensorNoise estimate_sensor_noise(const Log& log, const Eigen::VectorXd& torque_constant,
                                  std::vector<int>* never_rests = nullptr);

/// Parameters of the noise's joint count from the noise: σ² = noise² + step²/12 (the effort's
/// rounding), static dead band 3σ·√(1 + 1/5) (static_dead_band_from_noise with
/// the tracker's 12.5 ms = 5-sample window), pad hysteresis levels from the pad noise
/// (detector_settings_from_noise, 12-bit ADC step 0.0105 kPa), pad force gain for
/// `pad_gain_kpa_per_n` on the 25 cm² reference pad. The transition σ stay 0 until calibrated.
ReplayParameters estimator_parameters_from_noise(const SensorNoise& noise,
                                                 double pad_gain_kpa_per_n = 1.5);

/// Runs the estimator of `setup` over `samples` (trace_estimator).
EstimatorTrace replay_estimator(const ReplaySetup& setup, const std::vector<ReplaySample>& samples);

/// The speeds a log covers, per joint: max |q̇_j| over its finite samples [rad/s] (0 when none;
/// empty without samples).
/// Run on the contact-free calibration log it bounds the compensator's domain
/// (EstimatorParameters::compensator_speed_limit): the speeds over which its σ and the torque
/// alarm were calibrated, and, with calibration and training drawn from one scenario, trained.
ReplayVector speed_envelope(const std::vector<ReplaySample>& samples);

/// The accelerations a log covers, per joint: max |q̈_j| over the rows of its trace
/// (replay_estimator) as the estimator computed it — the compensator's q̈ input: the sample's,
/// or the filtered derivative of q̇ [rad/s²]. On the contact-free calibration log it bounds the
/// compensator's domain with speed_envelope (EstimatorParameters::compensator_acceleration_limit).
ReplayVector acceleration_envelope(const EstimatorTrace& tr);

/// calibrate_transition_sigma on contact-free `samples` with the setup's compensator; the result
/// is stored in setup.parameters (nominal_sigma, fused_sigma) and returned.
TransitionSigma<double, Eigen::Dynamic> calibrate_sigma(ReplaySetup& setup,
                                                        const std::vector<ReplaySample>& samples,
                                                        const std::string& source);

}  // namespace tpf::offline
