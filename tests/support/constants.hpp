// Constants shared by several test files (one definition, so a program's files can be compiled
// as one unity source).
#pragma once

#include <limits>

namespace tpf::test {

/// s, one cycle of the arm's 400 Hz loop.
inline constexpr double kPeriod = 1.0 / 400.0;
/// A quiet NaN: a missing sample or value.
inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
/// The project's 4-joint arm (data/arm4.robot.json) and its pad layout (data/arm4.pads.json).
inline constexpr int kArm4Joints = 4;
inline constexpr int kArm4Pads = 11;

}  // namespace tpf::test
