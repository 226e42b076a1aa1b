// Declared model: Coulomb and viscous friction of a joint and the friction held at rest,
// columns s, q̇_j, h (s = sgn(q̇_j) when moving else 0, h = the held sign at rest else 0).
#pragma once

#include <algorithm>
#include <string_view>

#include "offline/effects/design_context.hpp"
#include "offline/effects/feature_group.hpp"
#include "offline/effects/sample_row.hpp"
#include "offline/effects/written_model.hpp"

namespace tpf::offline {

struct JointFrictionColumns {
  static constexpr std::string_view key = "friction";
  static constexpr WrittenTo written_to = WrittenTo::kFriction;
  static constexpr bool kSharedGroupFirst = false;
  /// Column indices within the family.
  static constexpr int kCoulomb = 0, kViscous = 1, kHeldAtRest = 2;

  static bool offered(const DesignContext&, int joint) { return joint >= 0; }
  static GroupSpec group(const DesignContext&, int joint) {
    const std::string n = joint_suffix(joint);
    return {"Coulomb and viscous friction, " + joint_title(joint),
            {"fc" + n, "fv" + n, "rest" + n},
            kHeldAtRest};
  }
  static void fill(const SampleRow& row, int joint, double* out) {
    out[kCoulomb] = row.direction[joint];
    out[kViscous] = row.motion.dq[joint];
    out[kHeldAtRest] = row.held[joint];
  }
  /// The sliding levels the Stribeck curves start from (negative fits clipped to 0).
  static void write(const double* coefficients, int joint, WrittenModel& out) {
    out.linear.coulomb[joint] = out.linear.static_friction[joint] =
        std::max(coefficients[kCoulomb], 0.0);
    out.linear.viscous[joint] = std::max(coefficients[kViscous], 0.0);
  }
  /// The friction is declared: never removed.
  static void remove(int, NominalModelX&) {}
};

}  // namespace tpf::offline
