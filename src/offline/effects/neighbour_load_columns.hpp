// Candidate: friction of joint j growing with another joint's gravity load, |G_k|s, |G_k|q̇_j for
// the joint k ≠ j chosen on the declared model's residual (CandidateInputs::neighbour_load_source,
// choose_neighbour_loads) (written into the friction model: neighbour_load_coulomb β,
// neighbour_load_viscous γ).
#pragma once

#include <string_view>

#include "offline/effects/design_context.hpp"
#include "offline/effects/feature_group.hpp"
#include "offline/effects/sample_row.hpp"
#include "offline/effects/written_model.hpp"

namespace tpf::offline {

struct NeighbourLoadColumns {
  static constexpr std::string_view key = "neighbour_load_friction";
  static constexpr WrittenTo written_to = WrittenTo::kFriction;
  static constexpr bool kSharedGroupFirst = false;

  static int source(const CandidateInputs& inputs, int joint) {
    return inputs.neighbour_load_source[joint];
  }
  static bool offered(const DesignContext& c, int joint) {
    return joint >= 0 && c.inputs.neighbour_load_source.size() == c.joints &&
           source(c.inputs, joint) >= 0;
  }
  static GroupSpec group(const DesignContext& c, int joint) {
    const std::string n = joint_suffix(joint), k = joint_suffix(source(c.inputs, joint));
    GroupSpec spec{
        "friction growing with joint " + k + "'s load |G" + k + "|, " + joint_title(joint),
        {"beta" + n + "_" + k, "gamma" + n + "_" + k}};
    // Growing: a Coulomb level that falls as the load rises is some other effect's stand-in (on
    // the twin's cooling arm, |G2|·q̇1 stood in for joint 1's thermal viscous friction with β < 0).
    spec.dissipative = {0};
    return spec;
  }
  static void fill(const SampleRow& row, int joint, double* out) {
    const double load = row.inputs.abs_gravity(row.k, source(row.inputs, joint));
    out[0] = load * row.direction[joint];
    out[1] = load * row.motion.dq[joint];
  }
  static void write(const double* coefficients, int joint, WrittenModel& out) {
    const int k = source(out.inputs, joint);
    out.linear.neighbour_load_coulomb(joint, k) = coefficients[0];
    out.linear.neighbour_load_viscous(joint, k) = coefficients[1];
  }
  static void remove(int joint, NominalModelX& nominal) {
    nominal.friction.neighbour_load_coulomb.row(joint).setZero();
    nominal.friction.neighbour_load_viscous.row(joint).setZero();
  }
};

}  // namespace tpf::offline
