// Folder effects/: the typed registry of the design matrix's column families, one header each
// (the declared model and every candidate effect), read by identify/ and diagnose/, and by the
// measured study's candidates against the torque sensor (measured_study/sensor_candidates.cpp,
// which also reads the families listed in neither tuple below: EffortScaleColumns,
// ThermalCoulombColumns, and SelectedColumns of a family). It depends on samples/ (SampleRow) and
// report/'s number format only.
//
// The registration of the design matrix's column families: the declared model, then the library
// of candidate effects, each one type (see its header) with
//   key, written_to, kSharedGroupFirst,
//   offered(DesignContext, joint) / group(DesignContext, joint)   (joint −1: every joint at once),
//   fill(SampleRow, joint, out)          its columns of one joint row of a sample,
// or, for a family of several groups that act on chosen joints (a coupled motor per pair),
//   variants(DesignContext), group(DesignContext, variant), fill(SampleRow, joint, variant, out),
//   write(coefficients, joint, WrittenModel)  into the parameter file's model,
//   remove(joint, NominalModelX)         its part of a written model set to zero.
// Adding an effect = one header + one entry in CandidateColumns (and, when the run time evaluates
// it, its type in tpf/effects/added_effects.hpp).
#pragma once

#include <Eigen/Core>
#include <tuple>
#include <vector>

#include "offline/effects/asymmetric_friction_columns.hpp"
#include "offline/effects/coupled_motor_columns.hpp"
#include "offline/effects/coupling_columns.hpp"
#include "offline/effects/delay_columns.hpp"
#include "offline/effects/joint_friction_columns.hpp"
#include "offline/effects/load_friction_columns.hpp"
#include "offline/effects/motor_friction_columns.hpp"
#include "offline/effects/motor_ripple_columns.hpp"
#include "offline/effects/neighbour_load_columns.hpp"
#include "offline/effects/offset_columns.hpp"
#include "offline/effects/output_ripple_columns.hpp"
#include "offline/effects/payload_columns.hpp"
#include "offline/effects/relative_thermal_friction_columns.hpp"
#include "offline/effects/rigid_body_columns.hpp"
#include "offline/effects/spring_columns.hpp"
#include "offline/effects/thermal_friction_columns.hpp"

namespace tpf::offline {

/// Always in the design, in this order.
using DeclaredColumns = std::tuple<RigidBodyColumns, JointFrictionColumns, MotorFrictionColumns>;

/// The candidate library, in this order: the shared groups that come first (kSharedGroupFirst),
/// then per joint each type's group, then the other shared groups (joint −1).
using CandidateColumns =
    std::tuple<PayloadColumns, LoadFrictionColumns, OutputRippleColumns, MotorRippleColumns,
               ThermalFrictionColumns, OffsetColumns, AsymmetricFrictionColumns, SpringColumns,
               DelayColumns, CouplingColumns, NeighbourLoadColumns, RelativeThermalFrictionColumns,
               CoupledMotorColumns>;

/// Calls f.template operator()<Family>() for each type of the tuple `Families`, in order.
template <typename Families, typename F>
void for_each_family(F&& f) {
  [&f]<typename... Family>(std::tuple<Family...>*) {
    (f.template operator()<Family>(), ...);
  }(static_cast<Families*>(nullptr));
}

/// Calls f.template operator()<Family>() for the family types whose key is `key` (two thermal
/// types share theirs: one joint's and every joint's).
template <typename F>
void for_family_with_key(const std::string& key, F&& f) {
  const auto matching = [&]<typename Family>() {
    if (Family::key == key) f.template operator()<Family>();
  };
  for_each_family<DeclaredColumns>(matching);
  for_each_family<CandidateColumns>(matching);
}

/// Writes the coefficients `theta` holds for group g into `out`.
inline void write_group(const FeatureGroup& g, const Eigen::VectorXd& theta, WrittenModel& out) {
  std::vector<double> coefficients;
  for (int c : g.columns)
    coefficients.push_back(theta[c]);
  for_family_with_key(g.key,
                      [&]<typename Family>() { Family::write(coefficients.data(), g.joint, out); });
}

/// Sets group g's part of a written model to zero (no-op for what cannot be taken out: the rigid
/// body, the declared friction, a payload folded into the base, what was not written).
inline void remove_group(const FeatureGroup& g, NominalModelX& nominal) {
  for_family_with_key(g.key, [&]<typename Family>() { Family::remove(g.joint, nominal); });
}

}  // namespace tpf::offline
