// The friction compensators a controller names as a type, as RTNeural's ModelT names its layers:
// which network, its size and the scalar it is evaluated in. A kind's `For<S, N>` is the
// compensator class of an N-joint estimator in scalar S; `load` fills it from the weight files
// the offline tools write (find_compensator_weights).
#pragma once

#include <string>

#include "tpf/common/error.hpp"
#include "tpf/estimation/compensator.hpp"
#include "tpf/estimation/compensator_weight_files.hpp"
#include "tpf/nn/load_tcn_weights.hpp"
#include "tpf/nn/per_joint_tcn_compensator.hpp"
#include "tpf/nn/tcn.hpp"

namespace tpf {

/// Levels and taps of the compensator networks `tpf train` writes (receptive field 46 samples,
/// 115 ms at 400 Hz; docs/tcn.md).
inline constexpr int kCompensatorLevels = 4;
inline constexpr int kCompensatorKernel = 4;

namespace detail {
/// Refuses weight files of another layout or size than the compiled kind `kind`.
inline void require_weights(const CompensatorWeightFiles& w, CompensatorLayout layout, int hidden,
                            const std::string& kind) {
  if (w.layout == layout && (layout == CompensatorLayout::None || w.hidden == hidden)) return;
  throw Error::at(w.source, 0, "weights",
                  "holds " + describe(w) + "; this program is built for " + kind);
}
}  // namespace detail

/// No compensation: τ_TCN = 0 (the fused estimate is the nominal one).
struct NoCompensator {
  template <typename S, int N>
  using For = ZeroCompensator<S, N>;
  template <typename S, int N>
  static void load(For<S, N>&, const CompensatorWeightFiles& w) {
    detail::require_weights(w, CompensatorLayout::None, 0, "no friction compensator");
  }
};

/// One network of Hidden channels per joint (any joint count, Eigen::Dynamic too), evaluated in
/// NetScalar (float: twice the SIMD width;
/// BFloat16Weights: float with the hidden blocks' taps in bfloat16, half their bytes, the tools'
/// and the examples' kind; docs/tcn.md "Float or double"); the weight files
/// `<stem>.joint<j>.json`.
template <typename NetScalar, int Hidden, int Levels = kCompensatorLevels>
struct PerJointTcn {
  template <typename S, int N>
  using For = PerJointTcnCompensator<S, N, Hidden, Levels, NetScalar>;
  template <typename S, int N>
  static void load(For<S, N>& c, const CompensatorWeightFiles& w) {
    detail::require_weights(w, CompensatorLayout::PerJoint, Hidden,
                            "per-joint networks of " + std::to_string(Hidden) + " channels");
    const int n = c.joint_count();
    if (static_cast<int>(w.files.size()) != n)
      throw Error::at(w.source, 0, "weights",
                      "holds " + std::to_string(w.files.size()) +
                          " per-joint networks, the arm has " + std::to_string(n) + " joints");
    for (int j = 0; j < n; ++j)
      load_tcn_weights(w.files[static_cast<std::size_t>(j)], c.network(j));
  }
};

/// One network of Hidden channels for all joints (inputs 5N, outputs N), in the estimator's
/// scalar; one weight file. A fixed joint count only: the network's shape is compiled for N
/// (For<S, Eigen::Dynamic> is not a type).
template <int Hidden, int Levels = kCompensatorLevels>
struct AllJointsTcn {
  template <typename S, int N>
  requires(N != Eigen::Dynamic) using For =
      Tcn<S, kCompensatorInputsPerJoint * N, Hidden, Levels, kCompensatorKernel, N>;
  template <typename S, int N>
  requires(N != Eigen::Dynamic) static void load(For<S, N>& c, const CompensatorWeightFiles& w) {
    detail::require_weights(w, CompensatorLayout::AllJoints, Hidden,
                            "one network of " + std::to_string(Hidden) + " channels");
    load_tcn_weights(w.files.at(0), c);
  }
};

}  // namespace tpf
