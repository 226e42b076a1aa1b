// One named family of regressor columns of the design matrix: the declared model's or a candidate
// effect's, for one joint or for every joint.
#pragma once

#include <algorithm>
#include <string>
#include <vector>

namespace tpf::offline {

/// Where a family's coefficients go in the parameter file diagnose writes.
enum class WrittenTo {
  kRigidBody,     ///< the base parameters (the rigid body; a payload folds into it)
  kFriction,      ///< the friction model (StribeckParameters)
  kAddedEffects,  ///< an added effect the run time evaluates (tpf/effects/added_effects.hpp)
  kNothing,       ///< not evaluated at run time (OfflineOnlyEffects): reported, not written
  kRobotFile      ///< the robot file's to declare (a motor coupling): reported, not written
};

/// One named family of columns. Per-joint families act on that joint's effort only.
struct FeatureGroup {
  std::string key;    ///< the effect type's key: rigid, friction, load_friction, ripple, …
  std::string title;  ///< e.g. "load-dependent friction, joint 2"
  int joint = -1;     ///< 0-based; −1 = every joint's effort (payload; delay of every joint)
  bool declared = false;
  WrittenTo written_to = WrittenTo::kNothing;
  int held_column = -1;  ///< index in `columns` of the friction held at rest, −1 = none
  /// Keys of its joint's families it is judged on top of (a periodic effect must explain what an
  /// offset and a slope cannot: over a short range a sine is one or the other).
  std::vector<std::string> judged_beside;
  std::vector<int> columns;  ///< global feature indices, consecutive
  std::vector<std::string> column_names;
  /// Its term is unbounded (k·q) or periodic with few periods (a ripple of the output angle) in
  /// its joint's q: fitted over a range of q, it extrapolates outside it.
  bool extrapolates_in_q = false;
  /// On this log it cannot be told from the families it is judged beside (a ripple with under one
  /// period in its joint's range of motion): a claim of it names them too, "ambiguous between".
  bool indistinct_from_beside = false;
  /// The joints a group of joint −1 acts on, when not every joint (a coupled motor: its pair);
  /// its gain is scored on their weighted held-out SSE. Empty: `joint`'s, or every joint.
  std::vector<int> joints;
  /// Indices in `columns` of a friction's Coulomb and viscous coefficients, which must come out
  /// ≥ 0 for the group to be claimed (friction dissipates): a coupled motor's, and the Coulomb
  /// increment of a friction growing with another joint's load.
  std::vector<int> dissipative;
};

/// Whether group g's columns act on joint j's effort.
inline bool acts_on(const FeatureGroup& g, int j) {
  if (!g.joints.empty()) return std::find(g.joints.begin(), g.joints.end(), j) != g.joints.end();
  return g.joint == -1 || g.joint == j;
}

}  // namespace tpf::offline
