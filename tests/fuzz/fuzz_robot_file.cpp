// Fuzz target: any bytes as a robot file (beside copies of the arm's URDF and pad layout, so
// relative references resolve) → load_robot<double, 4> → load_pads. Contract: a model with finite
// drive data, or a one-line tpf::Error naming the robot file (or the file it refers to).
#include <cmath>

#include "fuzz_support.hpp"
#include "tpf/model/load_robot.hpp"
#include "tpf/skin/pad_layout.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const bool copied = [] {
    for (const char* name : {"arm4.urdf", "arm4.pads.json"})
      std::filesystem::copy_file(std::filesystem::path(TPF_FUZZ_DATA_DIR) / name,
                                 tpf::fuzz::scratch_dir() / name,
                                 std::filesystem::copy_options::overwrite_existing);
    return true;
  }();
  static_cast<void>(copied);
  const auto path = tpf::fuzz::write_input({data, size}, "input.robot.json");
  // A robot file may name another file; its errors then name that file, inside the scratch dir.
  tpf::fuzz::expect_clean_error(tpf::fuzz::scratch_dir().string(), [&] {
    const tpf::RobotDescription robot = tpf::load_robot_description(path);
    if (robot.drives.size() != robot.chain.joints.size())
      tpf::fuzz::violation("load_robot_description", "one drive per joint expected");
    if (!robot.gravity.allFinite())
      tpf::fuzz::violation("load_robot_description", "gravity is not finite");
    for (const tpf::DriveDescription& d : robot.drives)
      if (!std::isfinite(d.armature()) || !(d.gear_ratio > 0) || !std::isfinite(d.torque_constant))
        tpf::fuzz::violation("load_robot_description", "drive '" + d.joint + "' is not usable");
    if (robot.chain.joints.size() != 4) return;
    const auto model = tpf::make_model<double, 4>(robot);
    if (!robot.pads_file.empty()) static_cast<void>(tpf::load_pads(robot.pads_file, model));
  });
  return 0;
}
