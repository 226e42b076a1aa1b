// Compile-time shape of the friction-compensator TCN: dilations, ring lengths, receptive field.
#pragma once

#include <array>

namespace tpf {

/// Shape constants of a TCN with `Levels` residual blocks of kernel size `Kernel`.
///
/// Block l (l = 0 … Levels−1) is a causal convolution with dilation d_l = 2^l, so its output at
/// time t reads its input at t, t − d_l, …, t − (K−1)·d_l. The receptive field of the whole stack
/// is
///   R = 1 + (K − 1)·Σ_l d_l = 1 + (K − 1)·(2^Levels − 1)   [samples];
/// e.g. K = 4: Levels = 4 gives R = 46 samples = 115 ms at 400 Hz, Levels = 5 gives 94 = 235 ms.
template <int Levels, int Kernel>
struct TcnShape {
  static_assert(Levels >= 1 && Levels <= 16, "TCN needs 1 to 16 levels");
  static_assert(Kernel >= 2, "TCN kernel size must be at least 2");

  /// d_l = 2^l.
  static constexpr int dilation(int level) { return 1 << level; }
  /// Ring-buffer length of block l's input history: (K − 1)·d_l + 1 columns.
  static constexpr int history_length(int level) { return (Kernel - 1) * dilation(level) + 1; }
  /// R = 1 + (K − 1)·(2^Levels − 1) samples.
  static constexpr int receptive_field = 1 + (Kernel - 1) * ((1 << Levels) - 1);

  /// Column offsets of the histories of blocks first..Levels − 1 laid end to end in one buffer
  /// (entry l is block l's; the entries up to `first` are 0).
  static constexpr std::array<int, Levels + 1> history_offsets(int first) {
    std::array<int, Levels + 1> offset{};
    for (int l = first; l < Levels; ++l)
      offset[l + 1] = offset[l] + history_length(l);
    return offset;
  }
  /// Column offset of block l ≥ 1 in the one buffer that holds all hidden-block histories.
  static constexpr std::array<int, Levels + 1> hidden_history_offsets() {
    return history_offsets(1);
  }
  /// Σ_{l ≥ 1} ((K − 1)·d_l + 1): columns of all hidden-block histories together.
  static constexpr int hidden_history_columns = hidden_history_offsets()[Levels];

  /// Column offset of block l ≥ 0 in the one buffer of the blocks' pending sums (one slot per
  /// ring column: block l's pending ring is as long as its input ring).
  static constexpr std::array<int, Levels + 1> pending_offsets() { return history_offsets(0); }
  /// Σ_l ((K − 1)·d_l + 1): slots of all blocks' pending sums together.
  static constexpr int pending_columns = pending_offsets()[Levels];
};

}  // namespace tpf
