// Some of a family's columns, by their index within it: a family of its own whose columns are
// exactly those the whole family's fill() gives (the measured study's friction base is
// JointFrictionColumns' Coulomb and viscous columns, its friction held at rest the third).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "offline/effects/design_context.hpp"
#include "offline/effects/sample_row.hpp"

namespace tpf::offline {

/// `Columns` of `Family` (a family of one group per joint, at most kMaxColumns columns), in the
/// order given.
template <typename Family, int... Columns>
struct SelectedColumns {
  static constexpr int kMaxColumns = 32;
  static_assert(sizeof...(Columns) > 0 && ((Columns >= 0 && Columns < kMaxColumns) && ...));
  static constexpr std::string_view key = Family::key;
  static constexpr int kColumns = sizeof...(Columns);

  static bool offered(const DesignContext& c, int joint) { return Family::offered(c, joint); }
  /// The family's group with the selected columns' names.
  static GroupSpec group(const DesignContext& c, int joint) {
    const GroupSpec all = Family::group(c, joint);
    return {all.title, {all.column_names[static_cast<std::size_t>(Columns)]...}};
  }
  static void fill(const SampleRow& row, int joint, double* out) {
    double all[kMaxColumns];
    Family::fill(row, joint, all);
    int i = 0;
    ((out[i++] = all[Columns]), ...);
  }
};

}  // namespace tpf::offline
