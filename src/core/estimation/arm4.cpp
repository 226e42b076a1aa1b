// Start-up code of the arm4's compensator: which weight files a compensator path stands for.

#include "tpf/estimation/arm4.hpp"

#include "tpf/common/error.hpp"
#include "tpf/nn/tcn_weight_file.hpp"

namespace tpf {

std::filesystem::path joint_weight_path(const std::filesystem::path& path, int joint) {
  return path.parent_path() /
         (path.stem().string() + ".joint" + std::to_string(joint + 1) + ".json");
}

std::vector<std::string> compensator_files(const std::filesystem::path& path,
                                           CompensatorLayout& layout) {
  if (std::filesystem::exists(path)) {
    const TcnWeightFile file = read_tcn_weight_file(path.string());
    file.require_architecture(kCompensatorInputsPerJoint * kArmJoints, kArmHidden, kArmLevels, 4,
                              kArmJoints);
    layout = CompensatorLayout::AllJoints;
    return {path.string()};
  }
  std::vector<std::string> files;
  int hidden = 0;
  for (int j = 0; j < kArmJoints; ++j) {
    const auto p = joint_weight_path(path, j);
    if (!std::filesystem::exists(p))
      throw Error::at(path.string(), 0, "weights",
                      "no such weight file, nor per-joint files like " + p.string());
    const TcnWeightFile file = read_tcn_weight_file(p.string());
    if (j == 0) hidden = is_arm_joint_hidden(file.hidden) ? file.hidden : kArmJointHidden;
    file.require_architecture(kCompensatorInputsPerJoint, hidden, kArmLevels, 4, 1);
    files.push_back(p.string());
  }
  layout = CompensatorLayout::PerJoint;
  return files;
}

}  // namespace tpf
