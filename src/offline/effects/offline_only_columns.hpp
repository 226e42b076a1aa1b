// Base of the candidates the run time cannot evaluate (OfflineOnlyEffects): diagnosis fits and
// reports them; nothing of them is written to the parameter file, so nothing is removed.
#pragma once

#include "offline/effects/feature_group.hpp"
#include "offline/effects/written_model.hpp"

namespace tpf::offline {

struct OfflineOnlyColumns {
  static constexpr WrittenTo written_to = WrittenTo::kNothing;
  static constexpr bool kSharedGroupFirst = false;

  static void write(const double*, int, WrittenModel&) {}
  static void remove(int, NominalModelX&) {}
};

}  // namespace tpf::offline
