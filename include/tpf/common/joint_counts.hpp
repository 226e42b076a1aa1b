// The joint counts the compiled parts of tpf are built for: serial arms of 1 to kMaxJoints joints.
// Header-only code works for any N; the start-up loaders and the offline tools are instantiated
// for each count here.
#pragma once

namespace tpf {

inline constexpr int kMaxJoints = 7;

}  // namespace tpf

/// X(N) for N = 1 … kMaxJoints: explicit instantiations of code compiled for every joint count.
/// A library copy that serves one count only defines TPF_ONLY_JOINT_COUNT (the fuzzers'
/// instrumented core, src/core/CMakeLists.txt: they load 4-joint files).
#ifdef TPF_ONLY_JOINT_COUNT
#define TPF_FOR_EACH_JOINT_COUNT(X) X(TPF_ONLY_JOINT_COUNT)
#else
#define TPF_FOR_EACH_JOINT_COUNT(X) X(1) X(2) X(3) X(4) X(5) X(6) X(7)
#endif
