// A delay between the effort and the motion, τ(t) = τ_model(t + lead): an effect diagnosis finds
// and reports but the run time cannot evaluate (it keeps no past samples).
#pragma once

#include <string_view>

namespace tpf {

struct EffortDelay {
  static constexpr std::string_view key = "delay";  ///< diagnose's name of the effect

  /// Parameter file, "added_effects": "effort_lead_s": lead [s]; accepted only when absent or
  /// zero: a file that holds the effect is refused.
  template <typename Fields>
  static void refuse(Fields& added, int /*joints*/) {
    if (added.number("effort_lead_s", 0.0, -1.0, 1.0) != 0.0)
      added.fail("effort_lead_s",
                 "a delay between effort and motion is not evaluated by the run-time nominal "
                 "model (it keeps no past samples); set it to 0 or remove it to use the file "
                 "without it");
  }
};

}  // namespace tpf
