// Runs a command's work with the joint count N of a log, fixed at compile time (the core is
// templated on N): one place decides which N the tools are built for.
#pragma once

#include <string>
#include <utility>

#include "tpf/common/error.hpp"

namespace tpf::cli {

/// Calls `work.template operator()<N>()` with N = `joints` for N in 1..7, e.g.
///   with_joint_count(log.joint_count(), log.source, [&]<int N>() { run<N>(log, args); });
/// Any other count is refused with a tpf::Error naming `source`.
template <typename Work>
void with_joint_count(int joints, const std::string& source, Work&& work) {
  switch (joints) {
    case 1:
      return std::forward<Work>(work).template operator()<1>();
    case 2:
      return std::forward<Work>(work).template operator()<2>();
    case 3:
      return std::forward<Work>(work).template operator()<3>();
    case 4:
      return std::forward<Work>(work).template operator()<4>();
    case 5:
      return std::forward<Work>(work).template operator()<5>();
    case 6:
      return std::forward<Work>(work).template operator()<6>();
    case 7:
      return std::forward<Work>(work).template operator()<7>();
    default:
      throw Error::at(
          source, 0, "",
          "logs of 1 to 7 joints are supported, this one has " + std::to_string(joints));
  }
}

}  // namespace tpf::cli
