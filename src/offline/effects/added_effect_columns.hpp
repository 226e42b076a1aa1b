// The column family of a run-time added effect that is linear in its parameters: its columns are
// the effect's basis functions and its coefficients the effect's parameters of the joint, so the
// fit and the run-time torque share one definition.
#pragma once

#include <string_view>
#include <vector>

#include "offline/effects/feature_group.hpp"
#include "offline/effects/sample_row.hpp"
#include "offline/effects/written_model.hpp"

namespace tpf::offline {

/// Base of SpringColumns, OffsetColumns, CouplingColumns: everything but which joints it is
/// offered for and its names.
template <template <typename, int> class Effect>
struct AddedEffectColumns {
  using Type = Effect<double, Eigen::Dynamic>;
  static constexpr std::string_view key = Type::key;
  static constexpr WrittenTo written_to = WrittenTo::kAddedEffects;
  static constexpr bool kSharedGroupFirst = false;

  static void fill(const SampleRow& row, int joint, double* out) {
    Type::basis(row.motion, joint, out);
  }
  static void write(const double* coefficients, int joint, WrittenModel& out) {
    out.nominal.added.get<Effect>().set_coefficients(joint, coefficients);
  }
  static void remove(int joint, NominalModelX& nominal) {
    Type& effect = nominal.added.get<Effect>();
    const std::vector<double> zero(static_cast<std::size_t>(effect.columns()), 0.0);
    effect.set_coefficients(joint, zero.data());
  }
};

}  // namespace tpf::offline
