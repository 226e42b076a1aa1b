// Candidate: friction of joint j growing with another joint's gravity load, |G_k|s, |G_k|q̇_j for
// every k ≠ j (written into the friction model: neighbour_load_coulomb β, neighbour_load_viscous
// γ).
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

  static bool offered(const DesignContext& c, int joint) { return joint >= 0 && c.joints > 1; }
  static GroupSpec group(const DesignContext& c, int joint) {
    GroupSpec spec{"friction growing with the other joints' load |G_k|, " + joint_title(joint), {}};
    const std::string n = joint_suffix(joint);
    for (int k = 0; k < c.joints; ++k)
      if (k != joint) {
        spec.column_names.push_back("beta" + n + "_" + joint_suffix(k));
        spec.column_names.push_back("gamma" + n + "_" + joint_suffix(k));
      }
    return spec;
  }
  static void fill(const SampleRow& row, int joint, double* out) {
    const int joints = row.joints();
    for (int k = 0; k < joints; ++k)
      if (k != joint) {
        *out++ = row.inputs.abs_gravity(row.k, k) * row.direction[joint];
        *out++ = row.inputs.abs_gravity(row.k, k) * row.motion.dq[joint];
      }
  }
  static void write(const double* coefficients, int joint, WrittenModel& out) {
    const int joints = out.joints();
    for (int k = 0; k < joints; ++k)
      if (k != joint) {
        out.linear.neighbour_load_coulomb(joint, k) = *coefficients++;
        out.linear.neighbour_load_viscous(joint, k) = *coefficients++;
      }
  }
  static void remove(int joint, NominalModelX& nominal) {
    nominal.friction.neighbour_load_coulomb.row(joint).setZero();
    nominal.friction.neighbour_load_viscous.row(joint).setZero();
  }
};

}  // namespace tpf::offline
