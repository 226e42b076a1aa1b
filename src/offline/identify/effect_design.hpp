// The design matrix of identification and diagnosis: the declared model (rigid-body base
// parameters incl. armature, Coulomb and viscous friction, the friction held at rest) and a
// library of candidate physical effects, each a small named family of regressor columns of one
// effect type (offline/effects/effect_columns.hpp registers them).
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "offline/common/run_time_types.hpp"
#include "offline/effects/candidate_inputs.hpp"
#include "offline/effects/design_context.hpp"
#include "offline/effects/feature_group.hpp"
#include "offline/effects/sample_row.hpp"
#include "offline/fit/gram_fit.hpp"
#include "offline/samples/joint_samples.hpp"
#include "offline/samples/sample_regressors.hpp"
#include "tpf/dynamics/base_parameters.hpp"

namespace tpf::offline {

/// Features of every joint row of the samples (effort in N·m), for a model of any joint count N:
/// the rigid
/// columns' coefficients are SI base parameters, every other coefficient is in N·m per feature.
/// Row j of sample k (moving = |q̇_j| ≥ threshold, s = sgn(q̇_j) when moving else 0, h = held sign
/// at rest else 0, |G| = |G_j(q)| of the robot file's model [N·m]):
///   declared: Y_b(q,q̇,q̈)·e_j | s, q̇_j, h
///   load_friction: |G|s, |G|q̇_j, |G|h        ripple: sin(nq_j), cos(nq_j)
///   ripple_motor: sin(n r_j q_j), cos(n r_j q_j)   payload: Y(j, link N)·e_j (10 columns)
///   thermal: (T_j − T_ref)q̇_j, and for every joint at once (T_j − T_ref)·b_j·q̇_j (one shared
///            relative coefficient: viscous friction × (1 + β(T − T_ref)))
///   spring: q_j    offset: 1
///   asymmetric_friction: |s|, |q̇_j| (level τ_c ± a_c and viscous b ± a_v by direction)
///   neighbour_load_friction: |G_k|s, |G_k|q̇_j for the k ≠ j chosen on the residual
///   delay: (p_j(t) − p_j(t − lag))/lag of the rigid-body prediction over the searched lag
///          (coefficient = the effort's lead over the motion, s), one group per joint and one
///          for every joint at once (one shared lead)
///   coupling: q̇_k, q̈_k for every k ≠ j
///   coupled_motor (joints i and i + 1 only): share·s_θ, share·θ̇, share·θ̈ of a motor turning
///          with θ = a q_i + b q_{i+1}, share a on joint i and b on joint i + 1
/// Each family's columns are its effect type's fill(); those of an added effect are the basis
/// functions of its run-time torque (tpf/effects/), so a fit and the run time agree.
class EffectDesign {
 public:
  /// `regressors`: Y of `samples` (built with base.independent), shared with the caller's other
  /// designs; every pass of this design must be over samples with the same motion rows.
  EffectDesign(const ModelX& model, const BaseParameters& base, const JointSamples& samples,
               std::shared_ptr<const SampleRegressors> regressors, CandidateInputs candidates,
               double static_velocity);

  /// The columns of Y the families read for a `joints`-joint arm: the base columns, and the last
  /// link's (a payload) when the candidates are offered, and the motors' friction columns with
  /// `motor_friction` (a coupled model: MotorFrictionColumns). The SampleRegressors of a design
  /// must hold them.
  static std::vector<int> regressor_columns(int joints, const std::vector<int>& base_columns,
                                            bool candidates, bool motor_friction = false);

  int joints() const { return joints_; }
  int features() const { return features_; }
  /// The candidate inputs the design was built with.
  const CandidateInputs& candidates() const { return candidates_; }
  const std::vector<FeatureGroup>& groups() const { return groups_; }
  /// Columns of the declared model.
  std::vector<int> declared_columns() const;

  /// One pass over the samples (two threads): the Gram matrices per joint, regime and split.
  DesignGrams accumulate(const JointSamples& samples) const;
  /// Prediction φᵀθ per sample and joint (NaN where the sample is invalid).
  Eigen::MatrixXd predict(const JointSamples& samples, const Eigen::VectorXd& theta) const;
  /// φᵀθ_i for several parameter vectors in one pass over the samples (one regressor per sample).
  std::vector<Eigen::MatrixXd> predict_each(const JointSamples& samples,
                                            const std::vector<Eigen::VectorXd>& thetas) const;

 private:
  struct Workspace;
  /// Fills of one family: its columns of joint row `joint` of a sample (`variant`: which of a
  /// several-group family's groups, CoupledMotorColumns).
  using FillColumns = void (*)(const SampleRow&, int joint, int variant, double* out);
  /// Fills the local features of every joint row of sample k into `ws.local` (N × max local):
  /// those of the groups `filled` marks (one entry per group; empty: every group). The features
  /// of the other groups are left as they are (zero in a workspace zeroed once).
  void fill(const JointSamples& samples, Eigen::Index k, Workspace& ws,
            const std::vector<char>& filled = {}) const;
  /// Per group: whether any of `thetas` has a non-zero coefficient in its columns.
  std::vector<char> groups_in_use(const std::vector<Eigen::VectorXd>& thetas) const;
  /// Adds the groups the family types of the tuple `Families` offer, in registration order.
  template <typename Families>
  void add_families(const DesignContext& context);
  void add_group(FeatureGroup group, FillColumns fill, int variant = 0);
  /// local_, joint_groups_ and max_local_ of the groups.
  void index_joint_groups();
  /// Throws tpf::Error when `samples` are not the ones the regressors were computed for.
  void check_samples(const JointSamples& samples) const;

  ModelX model_;
  int joints_;
  std::shared_ptr<const SampleRegressors> regressors_;
  std::vector<int> base_columns_;
  CandidateInputs candidates_;
  double static_velocity_;
  bool has_temperature_;
  int features_ = 0;
  std::vector<FeatureGroup> groups_;
  std::vector<FillColumns> fills_;       ///< per group
  std::vector<int> variants_;            ///< per group: its variant (0 for most families)
  std::vector<std::vector<int>> local_;  ///< per joint: local index → global feature
  /// A group acting on a joint: its index, fill and column count (read per sample and joint).
  struct JointGroup {
    int group;
    FillColumns fill;
    int width;
    int variant;
  };
  std::vector<std::vector<JointGroup>> joint_groups_;  ///< per joint: the groups on it, in order
  int max_local_ = 0;
};

}  // namespace tpf::offline
