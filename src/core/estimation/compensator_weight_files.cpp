#include "tpf/estimation/compensator_weight_files.hpp"

#include <cmath>
#include <cstdio>

#include "core/common/unoptimised_when_sanitized.hpp"
#include "tpf/common/error.hpp"
#include "tpf/estimation/compensator.hpp"
#include "tpf/nn/tcn_weight_file.hpp"

TPF_UNOPTIMISED_WHEN_SANITIZED_BEGIN

namespace tpf {
namespace {

constexpr int kLevels = 4;  // the compensator networks of `tpf train` (compensator_types.hpp)
constexpr int kKernel = 4;

}  // namespace

std::filesystem::path joint_weight_path(const std::filesystem::path& path, int joint) {
  return path.parent_path() /
         (path.stem().string() + ".joint" + std::to_string(joint + 1) + ".json");
}

CompensatorWeightFiles find_compensator_weights(const std::filesystem::path& path, int joints) {
  CompensatorWeightFiles w;
  w.source = path.string();
  if (path.empty()) return w;
  if (std::filesystem::exists(path)) {
    const TcnWeightFile file = read_tcn_weight_file(path.string());
    file.require_architecture(kCompensatorInputsPerJoint * joints, file.hidden, kLevels, kKernel,
                              joints);
    w.layout = CompensatorLayout::AllJoints;
    w.hidden = file.hidden;
    w.files = {path.string()};
    return w;
  }
  for (int j = 0; j < joints; ++j) {
    const auto p = joint_weight_path(path, j);
    if (!std::filesystem::exists(p))
      throw Error::at(path.string(), 0, "weights",
                      "no such weight file, nor per-joint files like " + p.string());
    const TcnWeightFile file = read_tcn_weight_file(p.string());
    if (j == 0) w.hidden = file.hidden;
    file.require_architecture(kCompensatorInputsPerJoint, w.hidden, kLevels, kKernel, 1);
    w.files.push_back(p.string());
  }
  w.layout = CompensatorLayout::PerJoint;
  return w;
}

std::uint32_t compensated_joints(const CompensatorWeightFiles& weights, int joints, double min_gain,
                                 std::vector<std::string>* gated) {
  std::uint32_t mask = joints >= 32 ? ~0u : (1u << joints) - 1u;
  if (weights.layout == CompensatorLayout::None) return mask;
  const bool per_joint = weights.layout == CompensatorLayout::PerJoint;
  std::vector<TcnWeightFile> files;
  for (const std::string& f : weights.files)
    files.push_back(read_tcn_weight_file(f));
  for (int j = 0; j < joints; ++j) {
    const TcnWeightFile& file = files[per_joint ? static_cast<std::size_t>(j) : 0];
    const std::size_t output = per_joint ? 0 : static_cast<std::size_t>(j);
    for (std::size_t r = 0; r < file.held_out_gain.size(); ++r) {
      if (file.held_out_gain[r].size() <= output) continue;  // not scored
      const double gain = file.held_out_gain[r][output];
      if (!std::isfinite(gain) || gain >= min_gain) continue;
      mask &= ~(1u << j);
      if (gated) {
        char line[200];
        std::snprintf(line, sizeof line, "joint %d: held-out gain %+.1f %% at %s < %+.1f %%", j + 1,
                      100.0 * gain, TcnWeightFile::kHeldOutRegimes[r], 100.0 * min_gain);
        gated->push_back(line);
      }
      break;
    }
  }
  return mask;
}

std::string describe(const CompensatorWeightFiles& w) {
  switch (w.layout) {
    case CompensatorLayout::PerJoint:
      return "per-joint networks of " + std::to_string(w.hidden) + " channels";
    case CompensatorLayout::AllJoints:
      return "one network of " + std::to_string(w.hidden) + " channels";
    case CompensatorLayout::None:
      break;
  }
  return "no friction compensator";
}

}  // namespace tpf

TPF_UNOPTIMISED_WHEN_SANITIZED_END
