// The design matrix of identification and diagnosis: the declared model (rigid-body base
// parameters incl. armature, Coulomb and viscous friction, the friction held at rest) and a
// library of candidate physical effects, each a small named family of regressor columns.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "offline/identify/gram_fit.hpp"
#include "offline/identify/joint_samples.hpp"
#include "tpf/dynamics/base_parameters.hpp"
#include "tpf/model/model.hpp"

namespace tpf::offline {

/// The physical family a group of columns belongs to (FeatureGroup::key spells it out).
enum class FeatureKind {
  Rigid,
  Friction,
  Payload,
  LoadFriction,
  Ripple,
  RippleMotor,
  Thermal,
  Spring,
  Delay,
  Coupling,
  Offset,
  Asymmetry,
  NeighbourLoad
};

/// One named family of columns. Per-joint families act on that joint's effort only.
struct FeatureGroup {
  FeatureKind kind = FeatureKind::Rigid;
  std::string key;    ///< rigid, friction, load_friction, ripple, ripple_motor, payload, thermal,
                      ///< spring, delay, coupling, offset, asymmetric_friction,
                      ///< neighbour_load_friction
  std::string title;  ///< e.g. "load-dependent friction, joint 2"
  int joint = -1;     ///< 0-based; −1 = every joint's effort (payload; delay of every joint)
  bool declared = false;
  std::vector<int> columns;  ///< global feature indices
  std::vector<std::string> column_names;
};

/// What the candidate library needs from a first fit of the declared model.
struct CandidateInputs {
  bool enabled = false;
  Eigen::VectorXd ripple_cycles;  ///< per joint: periods per output revolution, 0 = none (also
                                  ///< when the motion covers less than one period)
  Eigen::VectorXd ripple_motor_cycles;  ///< per joint: periods per motor revolution, 0 = none
  Eigen::MatrixXd prediction_rate;  ///< d(declared prediction)/dt per sample and joint, or empty
  Eigen::MatrixXd abs_gravity;      ///< |G_j(q)| per sample and joint [N·m] (gravity_load)
  double reference_temperature = 25.0;  ///< °C
  /// Per joint: the declared fit's viscous coefficient b_j [N·m·s/rad], which the
  /// every-joint thermal candidate scales; empty = no every-joint thermal candidate.
  Eigen::VectorXd viscous;
};

/// Features of every joint row of the samples (effort in N·m), for an N-joint model: the rigid
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
///   neighbour_load_friction: |G_k|s, |G_k|q̇_j for every k ≠ j
///   delay: d(rigid-body prediction_j)/dt (coefficient = the effort's lead over the motion, s),
///          one group per joint and one for every joint at once (one shared lead)
///   coupling: q̇_k, q̈_k for every k ≠ j
template <int N>
class EffectDesign {
 public:
  EffectDesign(const Model<double, N>& model, const BaseParameters& base,
               const JointSamples& samples, CandidateInputs candidates, double static_velocity);

  int features() const { return features_; }
  const std::vector<FeatureGroup>& groups() const { return groups_; }
  /// Columns of the declared model.
  std::vector<int> declared_columns() const;

  /// One pass over the samples (two threads): the Gram matrices per joint, regime and split,
  /// of every `stride`-th sample (1 = all; a first, rough fit can afford fewer).
  DesignGrams accumulate(const JointSamples& samples, int stride = 1) const;
  /// Prediction φᵀθ per sample and joint (NaN where the sample is invalid).
  Eigen::MatrixXd predict(const JointSamples& samples, const Eigen::VectorXd& theta) const;
  /// φᵀθ_i for several parameter vectors in one pass over the samples (one regressor per sample).
  std::vector<Eigen::MatrixXd> predict_each(const JointSamples& samples,
                                            const std::vector<Eigen::VectorXd>& thetas) const;

 private:
  struct Workspace;
  /// Fills the local features of every joint row of sample k into `local` (N × max local size).
  void fill(const JointSamples& samples, Eigen::Index k, Workspace& ws) const;
  void add_group(FeatureKind kind, std::string key, std::string title, int joint,
                 std::vector<std::string> column_names);

  Model<double, N> model_;
  std::vector<int> base_columns_;
  CandidateInputs candidates_;
  double static_velocity_;
  bool has_temperature_;
  int features_ = 0;
  std::vector<FeatureGroup> groups_;
  std::vector<std::vector<int>> local_;         ///< per joint: local index → global feature
  std::vector<std::vector<int>> joint_groups_;  ///< per joint: the groups acting on it, in order
  int max_local_ = 0;
};

}  // namespace tpf::offline
