// Declared model of a coupled arm: Coulomb and viscous friction of every motor on its own
// velocity (C·q̇)_m, acting on the joints through Cᵀ: the regressor's per-motor columns
// C(m, j)·sgn((C·q̇)_m) and C(m, j)·(C·q̇)_m. One group over every joint's effort (a coupled
// motor's friction acts on several joints), offered only when the model's motors are coupled;
// identify fits the columns of the coupled motors (motor_is_coupled) and JointFrictionColumns for
// the others (the same columns there).
#pragma once

#include <algorithm>
#include <string_view>

#include "offline/common/run_time_types.hpp"
#include "offline/effects/design_context.hpp"
#include "offline/effects/feature_group.hpp"
#include "offline/effects/sample_row.hpp"
#include "offline/effects/written_model.hpp"

namespace tpf::offline {

/// Whether motor m acts on other joints than its own, or on its own with a rate other than q̇_m
/// (row m of C is not the unit row).
inline bool motor_is_coupled(const ModelX& model, int m) {
  if (!model.coupled) return false;
  for (int j = 0; j < model.joint_count(); ++j)
    if (model.coupling(m, j) != (j == m ? 1.0 : 0.0)) return true;
  return false;
}

struct MotorFrictionColumns {
  static constexpr std::string_view key = "motor_friction";
  static constexpr WrittenTo written_to = WrittenTo::kFriction;
  static constexpr bool kSharedGroupFirst = false;
  /// Column indices of motor m: 2m (Coulomb), 2m + 1 (viscous).
  static constexpr int kCoulomb = 0, kViscous = 1;

  static bool offered(const DesignContext& c, int joint) { return joint < 0 && c.coupled; }
  static GroupSpec group(const DesignContext& c, int) {
    GroupSpec spec{"Coulomb and viscous friction of the motors (through the coupling)", {}};
    for (int m = 0; m < c.joints; ++m) {
      spec.column_names.push_back("fc_motor" + joint_suffix(m));
      spec.column_names.push_back("fv_motor" + joint_suffix(m));
    }
    return spec;
  }
  /// The regressor's per-motor friction columns (EffectDesign::regressor_columns with
  /// motor_friction) of joint row `joint`.
  static void fill(const SampleRow& row, int joint, double* out) {
    const int n = row.joints();
    for (int m = 0; m < n; ++m) {
      out[2 * m + kCoulomb] = row.regressor(joint, 11 * n + m);
      out[2 * m + kViscous] = row.regressor(joint, 12 * n + m);
    }
  }
  /// The sliding levels of the coupled motors (negative fits clipped to 0).
  static void write(const double* coefficients, int, WrittenModel& out) {
    for (int m = 0; m < out.joints(); ++m) {
      if (!motor_is_coupled(out.nominal.model, m)) continue;
      out.linear.coulomb[m] = out.linear.static_friction[m] =
          std::max(coefficients[2 * m + kCoulomb], 0.0);
      out.linear.viscous[m] = std::max(coefficients[2 * m + kViscous], 0.0);
    }
  }
  static void remove(int, NominalModelX&) {}
};

}  // namespace tpf::offline
