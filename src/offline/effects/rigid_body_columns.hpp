// Declared model: the rigid body in base parameters (incl. armature), Y(q, q̇, q̈)·e_j of the
// base columns; its coefficients are the SI base parameters.
#pragma once

#include <string_view>

#include "offline/effects/design_context.hpp"
#include "offline/effects/feature_group.hpp"
#include "offline/effects/sample_row.hpp"
#include "offline/effects/written_model.hpp"
#include "tpf/estimation/nominal_model.hpp"

namespace tpf::offline {

struct RigidBodyColumns {
  static constexpr std::string_view key = "rigid";
  static constexpr WrittenTo written_to = WrittenTo::kRigidBody;
  static constexpr bool kSharedGroupFirst = true;

  static bool offered(const DesignContext&, int joint) { return joint < 0; }
  static GroupSpec group(const DesignContext& c, int) {
    GroupSpec spec{"rigid body (base parameters, armature)", {}};
    for (int column : c.base_columns)
      spec.column_names.push_back(regressor_column_name(c.joints, column));
    return spec;
  }
  static void fill(const SampleRow& row, int joint, double* out) {
    for (int column : row.base_columns)
      *out++ = row.regressor(joint, column);
  }
  /// The base parameters (a payload is added to them afterwards, see WrittenModel::payload).
  static void write(const double* coefficients, int, WrittenModel& out) {
    for (int i = 0; i < out.base.size(); ++i) {
      out.nominal.base_columns[i] = out.base.independent[i];
      out.nominal.base_values[i] = coefficients[i];
    }
  }
  /// The rigid body is declared: never removed.
  static void remove(int, NominalModelX&) {}
};

}  // namespace tpf::offline
