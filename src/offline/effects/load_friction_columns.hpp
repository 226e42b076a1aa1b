// Candidate: friction growing with the joint's gravity load, |G_j|s, |G_j|q̇_j, |G_j|h (written
// into the friction model: load_coulomb α_c, load_viscous α_v).
#pragma once

#include <algorithm>
#include <string_view>

#include "offline/effects/design_context.hpp"
#include "offline/effects/feature_group.hpp"
#include "offline/effects/sample_row.hpp"
#include "offline/effects/written_model.hpp"

namespace tpf::offline {

struct LoadFrictionColumns {
  static constexpr std::string_view key = "load_friction";
  static constexpr WrittenTo written_to = WrittenTo::kFriction;
  static constexpr bool kSharedGroupFirst = false;
  static constexpr int kHeldAtRest = 2;

  static bool offered(const DesignContext&, int joint) { return joint >= 0; }
  static GroupSpec group(const DesignContext&, int joint) {
    const std::string n = joint_suffix(joint);
    return {"load-dependent friction, " + joint_title(joint),
            {"alpha_c" + n, "alpha_v" + n, "alpha_rest" + n},
            kHeldAtRest};
  }
  static void fill(const SampleRow& row, int joint, double* out) {
    const double load = row.inputs.abs_gravity(row.k, joint);
    out[0] = load * row.direction[joint];
    out[1] = load * row.motion.dq[joint];
    out[kHeldAtRest] = load * row.held[joint];
  }
  static void write(const double* coefficients, int joint, WrittenModel& out) {
    out.linear.load_coulomb[joint] = std::max(coefficients[0], 0.0);
    out.linear.load_viscous[joint] = std::max(coefficients[1], 0.0);
    out.load_selected = out.load_selected || coefficients[0] != 0.0 || coefficients[1] != 0.0;
  }
  static void remove(int joint, NominalModelX& nominal) {
    nominal.friction.load_coulomb[joint] = nominal.friction.load_viscous[joint] = 0;
  }
};

}  // namespace tpf::offline
