// Folder diagnose/: `tpf diagnose` and its passes (the declared fit, residual analysis, effect
// selection, the CAD payload check, findings, report), on the samples and held-out split of
// samples/, the column families of effects/ and identify/'s design, fitted with fit/.
//
// `tpf diagnose`: from identify's fit of the declared model, trace the residual to the physical
// effects it lacks, add them, refit, and compare on held-out data.
#pragma once

#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "offline/identify/effect_design.hpp"
#include "offline/identify/identify.hpp"
#include "offline/regimes/regime_stats.hpp"

namespace tpf::offline {

struct DiagnoseOptions {
  SampleOptions samples;
  /// A candidate is selected only when it lowers the held-out residual sum of squares of the
  /// joints it acts on by at least this fraction (and the held-out BIC,
  /// n·ln(SSE_new/SSE_old) + k·ln n, decreases).
  double min_improvement = 0.10;
  int max_effects = 6;
  /// Identifiability: a candidate whose columns keep less than this share (sin² of the smallest
  /// principal angle) after projecting out the model's columns is indistinguishable from it …
  double min_distinct_share = 0.05;
  /// … and two candidates whose parts outside the model are this collinear (cos² of the
  /// smallest principal angle) are indistinguishable from each other: "ambiguous between".
  double max_shared_share = 0.9;
  /// A candidate of another joint nearly collinear (as above) with the one selected joins
  /// its claim when it passes on its own joint, or removes at least this fraction of the
  /// selected one's gain, both scored on the held-out SSE of the two joints.
  double cross_joint_gain_ratio = 0.8;
  /// A claimed coefficient must be this many standard errors from zero (Wald statistic per
  /// column, standard errors inflated for the residual's autocorrelation).
  double min_standard_errors = 3.0;
  /// IdentifyOptions::inertia_prior of the identify diagnose runs when it is not handed one's
  /// result. Every fit of the diagnosis has identify's strengths: the judged one for the
  /// selection on the training rows, the written one for the written model's refit on every row.
  bool inertia_prior = true;
  ProgressLine progress;
};

/// One claim of a diagnosis: an effect added to the model, named, or "ambiguous" between
/// candidates (or a candidate and the declared model) the data cannot tell apart.
struct Claim {
  std::vector<int> groups;  ///< indices into Diagnosis::groups; [0] is the one added to the model
  std::vector<double> improvements;  ///< held-out improvement of each (alone on the same model)
  /// Empty: each improvement is on the joint it acts on. Else the claim names candidates of
  /// different joints, and every improvement is on the weighted held-out SSE of these joints.
  std::vector<int> scored_joints;
  std::vector<double> coefficients, standard_errors;  ///< of groups[0]'s columns
  double distinct_share = 1.0;  ///< sin² of groups[0] against the model it was added to
  /// groups[0] judged beside other columns of its joint (CandidateTrial::model_improvement):
  /// its gain on top of them; improvements[0] is then its gain on the model alone. Else NaN.
  double beside_improvement = std::numeric_limits<double>::quiet_NaN();
  bool written = true;  ///< in the parameter file (the run time evaluates it)
  bool ambiguous() const { return groups.size() > 1; }
};

/// Held-out residual per joint: static, static-to-kinetic, moving, all.
using RegimeTable = std::vector<std::array<ResidualSums, 4>>;

/// What one candidate did when tried.
struct CandidateTrial {
  std::string key, title;
  int joint = -1;
  int round = 0;                ///< selection round (1 = tried on the declared model)
  double improvement = 0.0;     ///< fraction of held-out SSE removed on the joints it acts on
  double bic_change = 0.0;      ///< held-out BIC change (negative favours the candidate)
  double wald = 0.0;            ///< min over columns of |θ|/SE (SE inflated for autocorrelation)
  double distinct_share = 1.0;  ///< sin² of the smallest angle to the model's columns
  /// A candidate judged beside other columns of its joint (a periodic effect beside its joint's
  /// offset and spring, FeatureGroup::judged_beside): `improvement` is its gain on top of them,
  /// this its gain added to the model alone, which is what a claim writes. NaN otherwise.
  double model_improvement = std::numeric_limits<double>::quiet_NaN();
  /// A group acting on several joints (FeatureGroup::joints: a coupled motor on its pair): its
  /// smallest gain on one of them alone. A motor that drives two joints acts on both through Cᵀ,
  /// so it must lower each one's held-out error by min_improvement; NaN for other groups.
  double weakest_joint_improvement = std::numeric_limits<double>::quiet_NaN();
  /// A friction whose Coulomb or viscous coefficient came out negative (FeatureGroup::
  /// dissipative): no drive's friction pushes the motion, so it is not claimed.
  bool negative_friction = false;
  /// A several-file log: the smallest improvement on the other files, each held out in turn
  /// (fitted on the rest), and that file; NaN for a one-file log. A candidate is claimed only if
  /// this too reaches min_improvement: it lowers the held-out error of every file, not of one.
  double transfer_improvement = std::numeric_limits<double>::quiet_NaN();
  std::string transfer_file;
  /// An effect that extrapolates in q (FeatureGroup::extrapolates_in_q): the smallest
  /// improvement on the held-out samples whose q of its joint lies outside the range of q the fit
  /// saw, over the held-out groups that have such samples (outside_samples of them), and that
  /// group; NaN when no held-out group leaves the range (not tested).
  double outside_improvement = std::numeric_limits<double>::quiet_NaN();
  double outside_samples = 0;
  std::string outside_file;
  bool extrapolates = false;
  /// Passed every test itself, but stands in for a stronger candidate of its joint that failed
  /// the transfer test (stand_in_for, its title): beside that candidate's columns it lowers the
  /// held-out error by beside_failed_improvement < min_improvement, so it explains the residual
  /// the failed one explained and is not claimed in its place. Empty otherwise.
  std::string stand_in_for;
  double beside_failed_improvement = std::numeric_limits<double>::quiet_NaN();
  bool selected = false;
  /// Passes the tests on the selection's held-out file alone.
  bool passes_heldout(const DiagnoseOptions& o) const {
    return improvement >= o.min_improvement && bic_change < 0 && wald >= o.min_standard_errors &&
           !fails_alone(o) && !(weakest_joint_improvement < o.min_improvement) &&
           !negative_friction;
  }
  /// Explains the residual beside the columns it is judged with, but added to the model alone
  /// (what would be written) lowers the held-out error by less than min_improvement.
  bool fails_alone(const DiagnoseOptions& o) const {
    return !(model_improvement >= o.min_improvement || std::isnan(model_improvement));
  }
  /// Passed every test on the selection's held-out file but made another file worse.
  bool fails_transfer(const DiagnoseOptions& o) const {
    return passes_heldout(o) &&
           !(transfer_improvement >= o.min_improvement || std::isnan(transfer_improvement));
  }
  /// Passed the held-out file and the transfer, but its term, extrapolated outside the range of q
  /// it was fitted on, does not lower the error of the held-out samples there.
  bool fails_outside(const DiagnoseOptions& o) const {
    return passes_heldout(o) && !fails_transfer(o) && extrapolates &&
           !(outside_improvement >= o.min_improvement || std::isnan(outside_improvement));
  }
  /// Passed every test but stands in for a stronger candidate that failed the transfer test.
  bool stands_in(const DiagnoseOptions& o) const {
    return passes_heldout(o) && !fails_transfer(o) && !fails_outside(o) && !stand_in_for.empty();
  }
  /// Extrapolates in q and no held-out group left the range of q it was fitted on.
  bool outside_untested() const { return extrapolates && std::isnan(outside_improvement); }
};

/// A payload judged against the robot file's inertias (CAD), after the selection: the rigid body
/// is held at the robot file's base parameters; friction and the selected effects are refitted
/// with and without the 10 inertial parameters of a body on the last link. Only meaningful when
/// the robot file's inertias are right; an identified rigid body absorbs a payload (it is then
/// not a missing effect).
struct CadPayloadCheck {
  /// It removes ≥ min_improvement of the held-out SSE beyond the selected effects (and of every
  /// other file's, held out in turn), the BIC falls, and the mass is positive and
  /// ≥ min_standard_errors standard errors.
  bool claimed = false;
  double improvement = 0.0;  ///< fraction of the held-out moving SSE removed (all joints)
  double bic_change = 0.0;
  double mass = 0.0;                                 ///< kg
  double mass_standard_error = 0.0;                  ///< kg (inflated for autocorrelation)
  Vector3<double> centre = Vector3<double>::Zero();  ///< m, last link's frame
  /// Not claimed, but it would be without one of the selected effects whose columns its own
  /// nearly span (cos² of the smallest principal angle ≥ max_shared_share): "ambiguous between
  /// a payload and" those (indices into the groups), with those cos².
  std::vector<int> ambiguous_with;
  std::vector<double> ambiguous_shares;
  /// A several-file log: the smallest improvement on the other files held out in turn, and that
  /// file; NaN for a one-file log.
  double transfer_improvement = std::numeric_limits<double>::quiet_NaN();
  std::string transfer_file;
  bool ambiguous() const { return !ambiguous_with.empty(); }
};

/// What a diagnosis found, for an arm of any joint count (the samples' joint count): what the
/// passes after the fit (residual analysis, effect selection, findings, report) work on.
struct EffectDiagnosis {
  JointSamples samples;
  std::vector<FeatureGroup> groups;  ///< the whole library (declared + candidates)
  std::vector<int> selected;         ///< indices into groups, in selection order
  std::vector<Claim> claims;         ///< one per selected group, same order
  std::vector<CandidateTrial> trials;
  RegimeTable before, after;  ///< held-out, the linear fit the selection scores (held friction)
  /// Held-out, the models as `--params` writes them (predict_effort of the declared model as
  /// identify fits it, and of `nominal`: friction curves, no held friction at rest, no effect the
  /// run time cannot evaluate).
  std::vector<RegimeStats> written_before, written_after;
  Eigen::MatrixXd residual_written;  ///< effort − predict_effort(nominal), per sample and joint
  Eigen::VectorXd noise_floor;       ///< per joint: effort noise at rest (std of Δeffort/√2)
  /// Per joint: effort noise in motion, above the model's band (ResidualAnalysis::motion_noise).
  Eigen::VectorXd motion_noise;
  double model_band_hz = 0;  ///< that band's edge, the acceleration filter's cutoff [Hz]
  /// How the rows were held out: "by file: …", "by time blocks: …" or "none".
  std::string heldout_method;
  Eigen::MatrixXd residual_before, residual_after;  ///< per sample and joint
  std::vector<Eigen::MatrixXd> effect_terms;        ///< per selected group: its fitted effort term
  /// The held-out split in a sentence: which files are held out, and which are grouped because
  /// they repeat one motion (empty for a one-file log).
  std::string heldout_split;
  /// Per joint: [min, max] of q over the selection's training samples.
  std::vector<std::pair<double, double>> fit_range;
  std::vector<std::string> findings;  ///< plain sentences: what was found, what is left
  std::vector<std::string> notes;     ///< skipped candidates and why
  CadPayloadCheck cad_payload;
  /// The coupled-motor candidates, each pair's ratio as fitted (CandidateInputs::coupled_motors).
  std::vector<CoupledMotorCandidate> coupled_motors;
  /// The lag of the effort behind the rigid-body prediction the delay candidate differences over
  /// (search_effort_lag, s; 0 = none searched).
  double effort_lag_s = 0.0;
  /// Identify's inertia prior, which every fit of the diagnosis has: judged_strength the
  /// selection's (training rows), written_strength the written model's refit on every row.
  Identification::InertiaPrior inertia_prior;

  int joints() const { return static_cast<int>(noise_floor.size()); }
};

/// The diagnosis of an arm: what was found and the nominal model it writes.
struct Diagnosis : EffectDiagnosis {
  /// The declared model plus the selected effects, refitted on every row once judged
  /// (`refitted`; the held-out tables are of its fit on the training rows). With no effect
  /// written: identify's model (Identification::nominal).
  NominalModelX nominal;
  bool refitted = false;
  /// The same model fitted on the training rows: what residual_written, written_after and
  /// effect_terms are of (equal to `nominal` when nothing is held out).
  NominalModelX judged;
  /// Identify's model fitted on the training rows (Identification::judged: rigid body and
  /// friction curves, nothing added): what `written_before` scores; beside `nominal` it shows
  /// what a folded payload does.
  NominalModelX declared;
};

/// Runs the diagnosis of `log` for the arm of `model` (robot file, any joint count; the log must
/// have as many joints): identify (IdentifyOptions with options.samples and
/// options.inertia_prior, its defaults otherwise), then the diagnosis from its result. Never
/// hands ground truth (gt_* columns) to the fit.
Diagnosis diagnose(const Log& log, const ModelX& model, const DiagnoseOptions& options = {});

/// The same from samples already prepared (prepare_diagnosis, with `options.samples`).
Diagnosis diagnose(const Log& log, const ModelX& model, IdentificationSetup setup,
                   const DiagnoseOptions& options);

/// The diagnosis from identify's result: `identified` = identify(log, model, setup', …) on a
/// setup' whose base, regressors and gravity load `setup` shares (prepare_diagnosis), its samples
/// handed back (Identification::samples, moved into `setup`). Its declared fit on the training
/// rows is the selection's start, its residual the one analysed, its joint weights and inertia
/// prior strengths those of every fit; with no effect written, its model is the written one.
/// tpf::Error when `identified` is not of these samples.
Diagnosis diagnose(const Log& log, const ModelX& model, IdentificationSetup setup,
                   const Identification& identified, const DiagnoseOptions& options);

/// prepare_identification with the regressors diagnose reads (a superset of identify's), the
/// samples' gravity torque (gravity_torque, for check_sample_units) and the gravity load both
/// read, taken from it.
IdentificationSetup prepare_diagnosis(const Log& log, const ModelX& model,
                                      const SampleOptions& options);

}  // namespace tpf::offline
