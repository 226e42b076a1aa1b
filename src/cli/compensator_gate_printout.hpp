// The held-out gate as calibrate and validate print it: which joints run compensated.
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "tpf/estimation/compensator_weight_files.hpp"

namespace tpf::cli {

/// Prints "<tool>: compensated joints: 1, 3 (held-out gate, threshold +0.0 %)" and one line per
/// joint the gate turns off (the estimator runs it on the nominal residual). Nothing without a
/// compensator.
inline void print_compensated_joints(const char* tool, const CompensatorWeightFiles& weights,
                                     int joints, double min_gain) {
  if (weights.layout == CompensatorLayout::None) return;
  std::vector<std::string> gated;
  const std::uint32_t mask = compensated_joints(weights, joints, min_gain, &gated);
  std::string list;
  for (int j = 0; j < joints; ++j)
    if (mask & (1u << j)) list += (list.empty() ? "" : ", ") + std::to_string(j + 1);
  std::printf("%s: compensated joints: %s (held-out gate, threshold %+.1f %%)\n", tool,
              list.empty() ? "none" : list.c_str(), 100.0 * min_gain);
  for (const std::string& g : gated)
    std::printf("%s:   gated off, nominal residual: %s\n", tool, g.c_str());
}

}  // namespace tpf::cli
