// The quiet NaN the offline tools mark missing or undefined values with.
#pragma once

#include <limits>

namespace tpf::offline {

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace tpf::offline
