// Folder identify/: `tpf identify`: the declared model's design over the column families of
// effects/ (EffectDesign), its linear fit (fit/) with the robot file's inertias as a prior, the
// friction curves (Ceres), the held-out and consistency checks. It reads the samples of samples/
// and hands diagnose/ its result (Identification).
//
// `tpf identify`: the declared model of an arm (rigid-body base parameters with armature,
// Stribeck + viscous friction with load dependence) from a log, with held-out validation.
#pragma once

#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "offline/common/run_time_types.hpp"
#include "offline/identify/identification_setup.hpp"
#include "offline/log/log.hpp"
#include "offline/regimes/regime_stats.hpp"
#include "offline/samples/joint_samples.hpp"

namespace tpf::offline {

/// Receives one line of progress ("identify: pass 1/3 …").
using ProgressLine = std::function<void(const std::string&)>;

struct IdentifyOptions {
  SampleOptions samples;
  bool fit_load_friction = true;           ///< α_c, α_v free in the nonlinear friction fit
  int friction_samples_per_joint = 20000;  ///< subsample of moving training samples for Ceres
  /// Fit the friction of each joint whose joint torque sensor varies (tau_sensor<j>, a file at a
  /// time) against the sensor: target K_t·i − (τ_sensor + I_a·q̈) [N·m], the drive loss behind
  /// the gear, instead of effort − rigid-body prediction (joints without a usable sensor keep the
  /// latter). The rigid body is fitted from the effort as before.
  bool friction_from_sensor = false;
  /// Pull the rigid body toward the robot file's own inertias (a relative prior, ColumnPrior)
  /// with the strength of lowest held-out error among those that make M(q) positive definite at
  /// check_consistency's poses (choose_inertia_prior: 0 and a ladder of strengths, on the
  /// training rows); the written fit keeps it (or the next stronger where its M(q) needs it).
  /// Off: the plain fit, whatever M(q).
  bool inertia_prior = true;
  ProgressLine progress;
};

/// Physical consistency of an identified model.
struct ConsistencyCheck {
  double min_mass_eigenvalue = 0;  ///< smallest eigenvalue of M(q) over 200 seeded poses, kg·m²
  std::vector<std::string> problems;  ///< empty = consistent
  std::vector<std::string> checks;    ///< what was checked, for the report
  bool consistent() const { return problems.empty(); }
};

/// The identified model and its quality.
/// One strength of the inertia prior tried on the training rows (choose_inertia_prior).
struct PriorCandidate {
  double strength = 0;
  /// The linear fit's held-out error: √(Σ_j w_j SSE_j / Σ_j n_j) over the held-out rows of the
  /// fit's regimes, each joint's residual in units of its σ_j (w_j = 1/σ_j²); NaN: nothing is
  /// held out.
  double heldout_error = std::numeric_limits<double>::quiet_NaN();
  double min_eigenvalue = 0;       ///< of M(q) at check_consistency's poses [kg·m²]
  bool positive_definite = false;  ///< min_eigenvalue above the prior's floor
};

struct Identification {
  /// What the parameter file gets: fitted on the training rows, judged on the held-out ones,
  /// then refitted on every row (`refitted`) where rows were held out.
  NominalModelX nominal;
  bool refitted = false;
  /// The model fitted on the training rows: what `residual`, `heldout` and `training` score
  /// (equal to `nominal` when nothing is held out).
  NominalModelX judged;
  /// The linear friction of that fit on the effort (Coulomb, viscous per joint), where its
  /// curves start: with judged.base_values, the declared model's linear fit that diagnose
  /// starts its selection from.
  StribeckParametersX judged_linear;
  /// IdentifyOptions::fit_load_friction and friction_samples_per_joint: how the curves were
  /// fitted (diagnose fits those of its written model so).
  bool fit_load_friction = true;
  int friction_samples_per_joint = 20000;
  JointSamples samples;
  /// effort − prediction of the model fitted on the training rows, per sample and joint (NaN
  /// invalid): what `heldout` and `training` score.
  Eigen::MatrixXd residual;
  std::vector<RegimeStats> heldout;   ///< per joint, residual on held-out blocks per regime
  std::vector<RegimeStats> training;  ///< per joint, on the training blocks
  Eigen::VectorXd joint_weights;      ///< 1/σ_j² of the weighted least squares
  ConsistencyCheck consistency;
  /// IdentifyOptions::inertia_prior: the prior strength of the judged and of the written fit (0:
  /// none) and the smallest eigenvalue of M(q) [kg·m²] each had without it.
  struct InertiaPrior {
    bool asked = false;  ///< IdentifyOptions::inertia_prior
    double judged_strength = 0, written_strength = 0;
    double judged_min_eigenvalue = 0, written_min_eigenvalue = 0;
    double floor = 0;  ///< RobotFileInertiaPrior::floor (≤ 0: the robot file's own M(q) is not
                       ///< positive definite, the prior was not applied)
    std::vector<PriorCandidate> candidates;  ///< the strengths tried on the training rows
    std::string choice;                      ///< why judged_strength, in a sentence
  } inertia_prior;
  std::vector<std::string> friction_notes;  ///< bounds that bind, curve vs linear (FrictionCurves)
};

/// The friction curves of every joint and how they compare with the linear fit they start from.
struct FrictionCurves {
  StribeckParametersX parameters;
  Eigen::VectorXd heldout_rms_curve, heldout_rms_linear;  ///< per joint, friction target
  std::vector<std::string> notes;    ///< per joint: parameters at a bound, linear kept, …
  std::vector<char> linear_written;  ///< per joint: the linear fit is written, not the curve
};

/// Identifies the model of the arm described by `model` (the robot file, any joint count N; the
/// log must have as many joints) from `log`:
/// 1. weighted linear least squares of Y_b·π_b (SI base parameters, incl. armature) + τ_c·sgn(q̇)
///    + b·q̇ on the moving training samples (|q̇| ≥ threshold), weights per joint 1/σ_j² from
///    the residual std of an unweighted first fit (iterated once);
/// 2. per joint, Stribeck + load-dependent friction by Ceres on the friction target
///    effort − rigid prediction (moving training samples, subsampled);
/// 3. held-out residual per regime (interleaved blocks not used in 1–2) and a consistency check.
/// With options.friction_from_sensor, step 2 (and its linear start) uses the torque sensor; with
/// options.inertia_prior, step 1 is choose_inertia_prior (inertia_prior.hpp) for the judged fit
/// and refit_with_inertia_prior for the written one.
Identification identify(const Log& log, const ModelX& model, const IdentifyOptions& options = {});

/// The same from samples already prepared (prepare_identification(log, model, options.samples)
/// or prepare_diagnosis): their regressors are used where they are given. The samples end in
/// Identification::samples.
Identification identify(const Log& log, const ModelX& model, IdentificationSetup setup,
                        const IdentifyOptions& options);

/// M(q) ≻ 0 at 200 seeded poses (rigid body + armature from the base parameters), friction
/// coefficients non-negative, q̇_s > 0.
ConsistencyCheck check_consistency(const NominalModelX& nominal);

/// check_consistency's 200 seeded poses of `model`'s joints (uniform within their limits, else
/// in ±3 rad).
std::vector<Eigen::VectorXd> mass_check_poses(const ModelX& model);

/// The smallest eigenvalue of M(q) [kg·m²] (rigid body + armature from the base parameters) over
/// check_consistency's 200 seeded poses.
double min_mass_eigenvalue(const NominalModelX& nominal);

/// effort − (rigid + friction) of `nominal` on every sample (NaN where invalid).
Eigen::MatrixXd nominal_residual(const NominalModelX& nominal, const JointSamples& samples);

/// nominal_residual of each of `nominals`, models of one robot (equal `model`), in one pass: one
/// forward kinematics per sample for all of them.
std::vector<Eigen::MatrixXd> nominal_residuals(const std::vector<const NominalModelX*>& nominals,
                                               const JointSamples& samples);

/// Per-joint regime statistics of `residual` over the held-out (or training) samples only.
std::vector<RegimeStats> split_regime_stats(const JointSamples& samples,
                                            const Eigen::MatrixXd& residual, bool heldout);

/// Fits the Stribeck + load curve of every joint (Ceres, plain least squares; joints on two
/// threads, deterministic) on the friction target effort − rigid_prediction of the non-static
/// training samples, with the load |G_j(q)| of `abs_gravity` (gravity_load). `linear` is the
/// linear fit (τ_c = τ_s, b, α, and the direction asymmetry and neighbour load, which are held:
/// they are subtracted from the target and kept). On the held-out non-static samples the curve
/// must do at least as well as `linear` (its Coulomb and viscous clamped at ≥ 0): where it does
/// not, the linear fit is kept and a note says so; parameters that end at a bound are noted.
/// Samples where rigid_prediction is NaN are left out.
/// With a coupled `coupling` (Model::coupling, motors × joints; null or the identity: each joint
/// its own motor), entry m is motor m's curve, fitted on the motor side: on its velocity
/// (C·q̇)_m against the target (C⁻ᵀ·(effort − rigid_prediction))_m (the joint-side residual holds
/// Cᵀ·f(C·q̇)), on the samples where that velocity is at least 1e-4 and no joint of the motor's
/// row of C or C⁻ᵀ is invalid.
FrictionCurves fit_friction_curves(const JointSamples& samples,
                                   const Eigen::MatrixXd& rigid_prediction,
                                   const Eigen::MatrixXd& abs_gravity,
                                   const StribeckParametersX& linear, bool fit_load,
                                   int samples_per_joint,
                                   const Eigen::MatrixXd* coupling = nullptr);

class EffectDesign;

/// A linear fit θ of `design`'s columns as a nominal model without curves: its rigid base
/// parameters, and the linear friction (Coulomb + viscous) the curves start from.
struct LinearNominal {
  NominalModelX nominal;
  Eigen::VectorXd rigid_theta;  ///< θ's rigid-body columns, zero elsewhere
  StribeckParametersX linear;   ///< the linear friction the curves start from
};

LinearNominal linear_nominal(const ModelX& model, const EffectDesign& design,
                             const BaseParameters& base, const Eigen::VectorXd& theta);

/// The final fit of curves already judged (`judged`, from fit_friction_curves on the training
/// rows): every row, the held-out ones included; each joint keeps its linear fit or its curve as
/// chosen there, the curve refined from the judged one.
StribeckParametersX refit_friction_curves(const JointSamples& samples,
                                          const Eigen::MatrixXd& rigid_prediction,
                                          const Eigen::MatrixXd& abs_gravity,
                                          const StribeckParametersX& linear, bool fit_load,
                                          int samples_per_joint, const FrictionCurves& judged,
                                          const Eigen::MatrixXd* coupling = nullptr);

}  // namespace tpf::offline
