// Candidate: an unmodelled payload on the last link, Y(j, link N)·e_j (10 columns of the standard
// parameters); written folded into the base parameters.
#pragma once

#include <string_view>

#include "offline/effects/design_context.hpp"
#include "offline/effects/feature_group.hpp"
#include "offline/effects/sample_row.hpp"
#include "offline/effects/written_model.hpp"
#include "tpf/estimation/nominal_model.hpp"

namespace tpf::offline {

struct PayloadColumns {
  static constexpr std::string_view key = "payload";
  static constexpr WrittenTo written_to = WrittenTo::kRigidBody;
  static constexpr bool kSharedGroupFirst = true;
  static constexpr int kColumns = 10;  ///< m, mx, my, mz, Ixx … Izz of the last link

  static bool offered(const DesignContext&, int joint) { return joint < 0; }
  static GroupSpec group(const DesignContext& c, int) {
    GroupSpec spec{"unmodelled payload on the last link", {}};
    for (int p = 0; p < kColumns; ++p)
      spec.column_names.push_back("payload_" +
                                  regressor_column_name(c.joints, 10 * (c.joints - 1) + p));
    return spec;
  }
  static void fill(const SampleRow& row, int joint, double* out) {
    const int last_link = 10 * (row.joints() - 1);
    for (int p = 0; p < kColumns; ++p)
      *out++ = row.regressor(joint, last_link + p);
  }
  static void write(const double* coefficients, int, WrittenModel& out) {
    const int last_link = 10 * (out.joints() - 1);
    for (int p = 0; p < kColumns; ++p)
      out.payload[last_link + p] = coefficients[p];
  }
  /// Folded into the base parameters: it cannot be taken out again.
  static void remove(int, NominalModelX&) {}
};

}  // namespace tpf::offline
