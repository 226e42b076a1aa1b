// Candidate: direction-asymmetric friction, |s|, |q̇_j| (sliding level τ_c ± a_c and viscous
// b ± a_v by direction; written into the friction model: coulomb_asymmetry, viscous_asymmetry).
#pragma once

#include <cmath>
#include <string_view>

#include "offline/effects/design_context.hpp"
#include "offline/effects/feature_group.hpp"
#include "offline/effects/sample_row.hpp"
#include "offline/effects/written_model.hpp"

namespace tpf::offline {

struct AsymmetricFrictionColumns {
  static constexpr std::string_view key = "asymmetric_friction";
  static constexpr WrittenTo written_to = WrittenTo::kFriction;
  static constexpr bool kSharedGroupFirst = false;

  static bool offered(const DesignContext&, int joint) { return joint >= 0; }
  static GroupSpec group(const DesignContext&, int joint) {
    const std::string n = joint_suffix(joint);
    return {"direction-asymmetric friction (Coulomb, viscous), " + joint_title(joint),
            {"asym_c" + n, "asym_v" + n}};
  }
  static void fill(const SampleRow& row, int joint, double* out) {
    out[0] = std::abs(row.direction[joint]);
    out[1] = std::abs(row.motion.dq[joint]);
  }
  static void write(const double* coefficients, int joint, WrittenModel& out) {
    out.linear.coulomb_asymmetry[joint] = coefficients[0];
    out.linear.viscous_asymmetry[joint] = coefficients[1];
  }
  static void remove(int joint, NominalModelX& nominal) {
    nominal.friction.coulomb_asymmetry[joint] = nominal.friction.viscous_asymmetry[joint] = 0;
  }
};

}  // namespace tpf::offline
