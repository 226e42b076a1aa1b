// The column family of a run-time added effect that is linear in its parameters: its columns are
// the effect's basis functions and its coefficients the effect's parameters of the joint, so the
// fit and the run-time torque share one definition.
#pragma once

#include <array>
#include <string_view>

#include "offline/effects/feature_group.hpp"
#include "offline/effects/sample_row.hpp"
#include "offline/effects/written_model.hpp"

namespace tpf::offline {

/// Base of SpringColumns, OffsetColumns, CouplingColumns: everything but which joints it is
/// offered for and its names.
template <template <typename, int> class Effect>
struct AddedEffectColumns {
  static constexpr std::string_view key = Effect<double, 1>::key;
  static constexpr WrittenTo written_to = WrittenTo::kAddedEffects;
  static constexpr bool kSharedGroupFirst = false;

  template <int N>
  static void fill(const SampleRow<N>& row, int joint, double* out) {
    Effect<double, N>::basis(row.motion, joint, out);
  }
  template <int N>
  static void write(const double* coefficients, int joint, WrittenModel<N>& out) {
    out.nominal.added.template get<Effect>().set_coefficients(joint, coefficients);
  }
  template <int N>
  static void remove(int joint, NominalModel<double, N>& nominal) {
    const std::array<double, Effect<double, N>::kColumns> zero{};
    nominal.added.template get<Effect>().set_coefficients(joint, zero.data());
  }
};

}  // namespace tpf::offline
