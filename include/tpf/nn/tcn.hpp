// Streaming inference of the friction-compensator TCN: one sample in, the friction residual out.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <type_traits>
#include <utility>

#include "tpf/nn/bfloat16.hpp"
#include "tpf/nn/tcn_architecture.hpp"
#include "tpf/nn/tcn_weights.hpp"
#include "tpf/nn/tcn_x86_kernels.hpp"

namespace tpf {

/// A temporal convolutional network evaluated one sample at a time, with compile-time sizes.
///
///   In      inputs per step, e.g. compensator_input of one joint (5), or of all N joints (5·N)
///   Hidden  channels of every residual block
///   Levels  residual blocks; block l has dilation d_l = 2^l
///   Kernel  taps per causal convolution (4 by default)
///   Out     outputs per head, e.g. 1 (one joint) or N (all joints) [N·m]
///   HiddenWeights  S, or BFloat16Weights (S = float): blocks 1 … Levels−1's taps rounded to
///           bfloat16 when set, which halves their bytes in the x86 kernels (two columns a
///           word, BFloat16Pair); every path computes with the rounded taps, in float
///           (docs/tcn.md, "Precision")
///
/// With h_{−1}(t) = x(t) the raw input and d_l = 2^l, each block is
///   h_l(t) = ReLU( b_l + Σ_{j=0}^{K−1} W_{l,j}·h_{l−1}(t − j·d_l) + P_l·h_{l−1}(t) ),
/// P_0 a 1×1 projection In → Hidden (with the normalisation (x − μ)/σ folded into W_0, b_0, P_0),
/// P_l = I for l ≥ 1. Two linear heads read the last block at the current step:
///   low(t) = A_low·h_{L−1}(t) + c_low,  high(t) = A_high·h_{L−1}(t) + c_high,
///   output(t) = low(t) + high(t)   (the predicted friction residual τ_TCN, N·m).
/// The activation is ReLU. The output depends on the last R = 1 + (K − 1)·(2^Levels − 1) inputs.
///
/// Streaming: block l keeps a ring buffer of its last (K − 1)·d_l + 1 inputs, so `step` costs
/// Levels·K matrix–vector products (O(Levels·Hidden²·K)) whatever the dilation; it allocates
/// nothing, throws nothing and never branches on data size.
///
/// Kernel: on x86-64 (GCC, clang), whatever the translation unit's flags, a float or double
/// network whose hidden vector fills whole 32-byte registers (16 floats, 32 doubles, …) steps in
/// AVX-512 or AVX2 + FMA registers where the CPU has them (tcn_x86_kernels.hpp; chosen when the
/// Tcn is constructed, kernel()), equal to the portable path to rounding. These kernels also
/// keep each block's pending sums (the lagged taps' part of a future z, rebuild_pending), so
/// that each broadcast input serves all K taps. Elsewhere, the compile-time path below (Eigen,
/// add_taps), which reads only the rings.
template <typename S, int In, int Hidden, int Levels, int Kernel = 4, int Out = 1,
          typename HiddenWeights = S>
class Tcn {
  static constexpr bool kBFloat16 = std::is_same_v<HiddenWeights, BFloat16Weights>;
  static_assert(std::is_same_v<HiddenWeights, S> ||
                    (kBFloat16 && std::is_same_v<S, float> && Hidden % 2 == 0),
                "hidden weights in S, or in bfloat16 for a float network of even width");
  /// What the x86 kernels read of a hidden block's tap: S, or two columns a word.
  using HiddenTap = std::conditional_t<kBFloat16, BFloat16Pair, S>;

 public:
  using Scalar = S;
  using Shape = TcnShape<Levels, Kernel>;
  using Weights = TcnWeights<S, In, Hidden, Levels, Kernel, Out>;
  using Input = Eigen::Matrix<S, In, 1>;
  using Output = Eigen::Matrix<S, Out, 1>;
  using HiddenVector = Eigen::Matrix<S, Hidden, 1>;

  static constexpr int kInputs = In;
  static constexpr int kHidden = Hidden;
  static constexpr int kLevels = Levels;
  static constexpr int kKernel = Kernel;
  static constexpr int kOutputs = Out;
  /// R = 1 + (K − 1)·(2^Levels − 1) samples.
  static constexpr int kReceptiveField = Shape::receptive_field;

  /// All-zero weights and history (output 0) until weights are loaded, see load_tcn_weights.
  Tcn() { clear_history(); }
  explicit Tcn(const Weights& weights) : weights_(weights) {
    store_hidden_taps();
    clear_history();
  }

  /// How step() computes: preferred_tcn_kernel<S, Hidden>() unless use_kernel changed it.
  TcnKernel kernel() const noexcept { return kernel_; }
  /// Makes step() compute with `kernel` if this CPU runs it and it fits this shape (returns
  /// true), else changes nothing (false). For tests and benchmarks: each kernel's result equals
  /// the others' to rounding only.
  bool use_kernel(TcnKernel kernel) noexcept {
    if (!tcn_kernel_fits<S, Hidden>(kernel) || !tcn_kernel_supported(kernel)) return false;
    kernel_ = kernel;
    rebuild_pending();
    return true;
  }

  /// The weights as evaluated (with BFloat16Weights, the hidden blocks' taps rounded).
  const Weights& weights() const noexcept { return weights_; }
  /// Replaces the weights and clears the history, as a Tcn constructed with them: the rings (and
  /// the kernels' pending sums) hold the old network's activations, which the new one must not
  /// read. Call reset(x̄) to prewarm. Start-up code (copies the weights).
  void set_weights(const Weights& weights) noexcept {
    weights_ = weights;
    store_hidden_taps();
    clear_history();
  }

  /// Prewarms every block's history with the activations a constant input x̄ produces, i.e. the
  /// state reached after feeding x̄ for R steps: h_l = ReLU(b_l + (Σ_j W_{l,j} + P_l)·h_{l−1}).
  /// Also sets low(), high() and output() to their steady values.
  void reset(const Input& steady_input) noexcept {
    last_input_ = steady_input;
    input_history_.colwise() = steady_input;
    heads_.fill(0);
    hidden_.noalias() = weights_.input_bias + weights_.input_projection * steady_input;
    for (int j = 0; j < Kernel; ++j)
      hidden_.noalias() += weights_.input_taps[j] * steady_input;
    hidden_ = hidden_.cwiseMax(S(0));
    for (int l = 1; l < Levels; ++l) {
      for (int c = 0; c < Shape::history_length(l); ++c)
        history_column(l, c) = hidden_;
      HiddenVector z = weights_.bias[l - 1] + hidden_;
      for (int j = 0; j < Kernel; ++j)
        z.noalias() += weights_.taps[l - 1][j] * hidden_;
      hidden_ = z.cwiseMax(S(0));
    }
    apply_heads();
    rebuild_pending();
  }

  /// Advances one sample: pushes x(t) and returns output(t) = low(t) + high(t) [N·m].
  /// A sample with a non-finite value is flagged (skipped_inputs() counts it) and replaced by the
  /// last finite one, so it cannot poison the next R outputs.
  const Output& step(const Input& raw_input) noexcept {
    const bool finite = raw_input.allFinite();
    skipped_inputs_ += finite ? 0 : 1;
    if (finite) last_input_ = raw_input;
    const Input& input = last_input_;
    int head = heads_[0];
    input_history_.col(head) = input;
#ifdef TPF_TCN_DISPATCH
    if (kernel_ != TcnKernel::Portable) {
      step_in_registers();
      return output_;
    }
#endif
    {
      std::array<const S*, Kernel> columns;
      for (int j = 0; j < Kernel; ++j)
        columns[j] = input_history_.col(wrap(head - j, Kernel)).data();
      hidden_.noalias() = weights_.input_bias + weights_.input_projection * input;
      add_taps(hidden_, weights_.input_taps, columns);
    }
    heads_[0] = next(head, Kernel);
    hidden_ = hidden_.cwiseMax(S(0));

    for (int l = 1; l < Levels; ++l) {
      const int length = Shape::history_length(l);
      const int dilation = Shape::dilation(l);
      head = heads_[l];
      history_column(l, head) = hidden_;
      std::array<const S*, Kernel> columns;
      for (int j = 0; j < Kernel; ++j)
        columns[j] = history_column(l, wrap(head - j * dilation, length)).data();
      HiddenVector z = weights_.bias[l - 1] + hidden_;
      add_taps(z, weights_.taps[l - 1], columns);
      heads_[l] = next(head, length);
      hidden_ = z.cwiseMax(S(0));
    }
    apply_heads();
    return output_;
  }

  /// Steps M networks of this shape together, network n on inputs[n]; then nets[n].output() is
  /// what nets[n].step(inputs[n]) would return, bit for bit: each network performs the same
  /// operations in the same order, interleaved with the others column by column (networks
  /// whose kernel() is not Portable step in turn, each with its kernel). One network's
  /// step is a chain of dependent multiply-adds that leaves the vector units waiting on their
  /// latency; the networks' chains are independent, so interleaved they overlap
  /// (docs/performance.md). Groups of kInterleave networks at a time, as many as keep their
  /// accumulators in half the vector registers. Where add_taps already sums by columns into
  /// several accumulators (a hidden vector in one register) the networks step in turn, which
  /// measured as fast. Networks stepped in turn go from the last to the first if `backwards`: a
  /// caller that alternates it starts each call on the weights the previous one used last, still
  /// in the L1 cache where all M networks' weights are not (the order changes no result).
  /// Allocation-free.
  template <std::size_t M>
  static void step_together(std::array<Tcn, M>& nets, const std::array<Input, M>& inputs,
                            bool backwards = false) noexcept {
#ifdef TPF_TCN_DISPATCH
    if (std::any_of(nets.begin(), nets.end(),
                    [](const Tcn& t) { return t.kernel_ != TcnKernel::Portable; })) {
      for (std::size_t i = 0; i < M; ++i) {
        const std::size_t n = backwards ? M - 1 - i : i;
        nets[n].step(inputs[n]);
      }
      return;
    }
#else
    (void)backwards;
#endif
    if constexpr (kColumnAccumulators > 1) {
      // Each step already keeps several independent chains busy (add_taps): in turn is as fast.
      for (std::size_t n = 0; n < M; ++n)
        nets[n].step(inputs[n]);
      return;
    }
    for (std::size_t first = 0; first < M; first += kInterleave) {
      if constexpr (M % kInterleave == 0) {
        step_group<kInterleave>(&nets[first], &inputs[first]);
      } else {
        if (first + kInterleave <= M)
          step_group<kInterleave>(&nets[first], &inputs[first]);
        else
          step_rest<M % kInterleave>(&nets[first], &inputs[first]);
      }
    }
  }

  /// Low-frequency part of the last output [N·m].
  const Output& low() const noexcept {
    return low_;
  }
  /// High-frequency part of the last output [N·m].
  const Output& high() const noexcept {
    return high_;
  }
  /// low() + high() [N·m].
  const Output& output() const noexcept {
    return output_;
  }
  /// Number of non-finite samples replaced since construction.
  long skipped_inputs() const noexcept {
    return skipped_inputs_;
  }

 private:
  using HiddenColumn = Eigen::Map<HiddenVector, Eigen::Unaligned>;

#ifdef TPF_TCN_DISPATCH
  /// step() after x(t) is in the input ring, in kernel_'s registers (tcn_x86_kernels.hpp).
  void step_in_registers() noexcept {
    if constexpr (tcn_kernel_fits<S, Hidden>(TcnKernel::Avx2)) {
      S low = 0, high = 0;
      const TcnStepBuffers<S> buffers{input_history_.data(),
                                      heads_[0],
                                      hidden_history_.data(),
                                      heads_.data(),
                                      pending_.data(),
                                      hidden_.data(),
                                      &low,
                                      &high};
      bool done = false;
      if constexpr (tcn_kernel_fits<S, Hidden>(TcnKernel::Avx512)) {
        if (kernel_ == TcnKernel::Avx512) {
          tcn_x86::step_avx512(weights_, buffers, paired_taps_.data());
          done = true;
        }
      }
      if (!done) tcn_x86::step_avx2(weights_, buffers, paired_taps_.data());
      heads_[0] = next(heads_[0], Kernel);
      for (int l = 1; l < Levels; ++l)
        heads_[l] = next(heads_[l], Shape::history_length(l));
      if constexpr (Out == 1) {
        low_[0] = low;
        high_[0] = high;
        output_ = low_ + high_;
      } else {
        apply_heads();
      }
    }
  }
#endif

  /// With BFloat16Weights: rounds the hidden blocks' taps in weights_ to bfloat16 and packs them,
  /// two columns a word, into paired_taps_ (what the x86 kernels read); nothing otherwise.
  void store_hidden_taps() noexcept {
    if constexpr (kBFloat16) {
      BFloat16Pair* out = paired_taps_.data();
      for (auto& block : weights_.taps)
        for (auto& tap : block) {
          for (int c = 0; c < Hidden; c += 2)
            for (int r = 0; r < Hidden; ++r) {
              *out = bfloat16_pair(tap(r, c), tap(r, c + 1));
              tap(r, c) = pair_even(*out);
              tap(r, c + 1) = pair_odd(*out++);
            }
        }
    }
  }

  /// i in [−n, n) ↦ i mod n.
  static int wrap(int i, int n) noexcept {
    return i < 0 ? i + n : i;
  }
  /// (i + 1) mod n for i in [0, n).
  static int next(int i, int n) noexcept {
    return i + 1 == n ? 0 : i + 1;
  }

  HiddenColumn history_column(int level, int column) noexcept {
    return HiddenColumn(hidden_history_.data() + Hidden * (kHiddenOffsets[level] + column));
  }
  /// Block l's input at ring column `column` (the raw input for l = 0).
  template <int Columns>
  Eigen::Map<const Eigen::Matrix<S, Columns, 1>, Eigen::Unaligned> block_input(
      int level, int column) const noexcept {
    const S* p = level == 0 ? input_history_.col(column).data()
                            : hidden_history_.data() + Hidden * (kHiddenOffsets[level] + column);
    return Eigen::Map<const Eigen::Matrix<S, Columns, 1>, Eigen::Unaligned>(p);
  }

  /// Sets the x86 kernels' pending sums (TcnStepBuffers::pending) from the rings: slot
  /// heads_[l] + m of block l (m = 0 … (K − 1)·d_l) to Σ_{j ≥ 1, j·d_l > m} W_{l,j}·h_{l−1}(t + m −
  /// j·d_l), t the next step. After reset() and a change of kernel; the kernels keep them from
  /// then on (the portable path reads only the rings).
  void rebuild_pending() noexcept {
    if (kernel_ == TcnKernel::Portable) return;
    for (int l = 0; l < Levels; ++l) {
      const int length = Shape::history_length(l), dilation = Shape::dilation(l);
      for (int m = 0; m < length; ++m) {
        HiddenColumn slot(pending_.data() +
                          Hidden * (kPendingOffsets[l] + (heads_[l] + m) % length));
        slot.setZero();
        for (int j = Kernel - 1; j >= 1 && j * dilation > m; --j) {
          const int column = wrap(heads_[l] + m - j * dilation, length);
          if (l == 0)
            slot.noalias() += weights_.input_taps[j] * block_input<In>(0, column);
          else
            slot.noalias() += weights_.taps[l - 1][j] * block_input<Hidden>(l, column);
        }
      }
    }
  }

  /// Vector registers of the target (AVX-512: 32 × 64 bytes; AVX: 16 × 32; SSE2: 16 × 16).
#if defined(__AVX512F__)
  static constexpr int kVectorBytes = 64, kVectorRegisters = 32;
#elif defined(__AVX__)
  static constexpr int kVectorBytes = 32, kVectorRegisters = 16;
#else
  static constexpr int kVectorBytes = 16, kVectorRegisters = 16;
#endif
  /// Whether one accumulator per tap fits in the vector registers: 16 float channels fill one
  /// AVX-512 register (four accumulators: 4 of 32 registers), four SSE2 registers (16 of 16).
  static constexpr bool kAccumulatorPerTap =
      Kernel * ((Hidden * int(sizeof(S)) + kVectorBytes - 1) / kVectorBytes) <= kVectorRegisters;

  /// Vector registers one Hidden-vector accumulator takes.
  static constexpr int kVectorsPerHidden =
      (Hidden * int(sizeof(S)) + kVectorBytes - 1) / kVectorBytes;
  /// Where a Hidden vector fits one register (16 floats in AVX-512), add_taps deals the columns to
  /// this many accumulators (an FMA's latency over its throughput); otherwise 1 (per-tap sums).
  static constexpr int kColumnAccumulators = kVectorsPerHidden == 1 ? 4 : 1;

  /// z += Σ_j W_j·x_j over the K taps, one column axpy at a time (keeps the sums in registers,
  /// 4–14 % faster than Eigen's general matrix–vector kernel at these sizes, docs/tcn.md).
  /// Where a Hidden vector is one register, see add_taps_by_columns. Otherwise, where the
  /// registers allow, each tap has its own accumulator and the K sums meet z at the end: the
  /// multiply-adds then form K independent chains instead of one through z, which a core with wide
  /// vector units overlaps instead of waiting on each add (docs/performance.md); the sums are
  /// ordered differently, equal to rounding. Otherwise one chain through z, as registers allow.
  template <typename Matrix>
  static void add_taps(HiddenVector& z, const std::array<Matrix, Kernel>& w,
                       const std::array<const S*, Kernel>& x) noexcept {
    constexpr int columns = Matrix::ColsAtCompileTime;
    if constexpr (kColumnAccumulators > 1) {
      add_taps_by_columns(z, w, x);
    } else if constexpr (kAccumulatorPerTap) {
      std::array<HiddenVector, Kernel> partial;
      for (int j = 0; j < Kernel; ++j)
        partial[j].noalias() = w[j].col(0) * x[j][0];
      for (int c = 1; c < columns; ++c)
        for (int j = 0; j < Kernel; ++j)
          partial[j].noalias() += w[j].col(c) * x[j][c];
      for (int j = 0; j < Kernel; ++j)
        z += partial[j];
    } else {
      for (int j = 0; j < Kernel; ++j)
        for (int c = 0; c < columns; ++c)
          z.noalias() += w[j].col(c) * x[j][c];
    }
  }

  /// add_taps with the K·columns axpys dealt in turn to kColumnAccumulators partial sums, the
  /// lagged taps (j ≥ 1, known before this step) first and the current tap (j = 0, the input just
  /// computed) last, then summed pairwise into z. The chains are independent, so the vector unit
  /// stays busy, and what waits on the previous block's output is only columns/A multiply-adds
  /// per chain instead of all of tap 0 (the block-to-block critical path of a step); the sums
  /// are ordered differently from the per-tap form, equal to rounding.
  template <typename Matrix>
  static void add_taps_by_columns(HiddenVector& z, const std::array<Matrix, Kernel>& w,
                                  const std::array<const S*, Kernel>& x) noexcept {
    constexpr int columns = Matrix::ColsAtCompileTime;
    constexpr int accumulators = kColumnAccumulators;
    static_assert(accumulators == 4, "the pairwise sum at the end is written for four");
    std::array<HiddenVector, accumulators> partial;
    for_each<accumulators>([&](auto a) { partial[a].setZero(); });
    auto add_tap = [&](int j) {
      for (int first = 0; first < columns; first += accumulators)
        for_each<accumulators>([&](auto a) {
          if (first + int(a) < columns)
            partial[a].noalias() += w[j].col(first + a) * x[j][first + a];
        });
    };
    for (int j = Kernel - 1; j > 0; --j)
      add_tap(j);
    add_tap(0);
    z += (partial[0] + partial[1]) + (partial[2] + partial[3]);
  }

  /// Networks stepped together: as many as keep one accumulator each in half the registers (the
  /// interleaved loops keep one accumulator per network live, see add_taps_together), 1 to 8.
  static constexpr std::size_t kInterleave =
      std::size_t(std::clamp(kVectorRegisters / 2 / kVectorsPerHidden, 1, 8));

  template <std::size_t G>
  static void step_rest(Tcn* nets, const Input* inputs) noexcept {
    if constexpr (G > 0) step_group<G>(nets, inputs);
  }

  /// step() of G networks, interleaved (see step_together).
  template <std::size_t G>
  static void step_group(Tcn* nets, const Input* inputs) noexcept {
    std::array<std::array<const S*, Kernel>, G> columns;
    std::array<HiddenVector, G> z;
    for (std::size_t n = 0; n < G; ++n) {
      Tcn& t = nets[n];
      const bool finite = inputs[n].allFinite();
      t.skipped_inputs_ += finite ? 0 : 1;
      if (finite) t.last_input_ = inputs[n];
      const int head = t.heads_[0];
      t.input_history_.col(head) = t.last_input_;
      for (int j = 0; j < Kernel; ++j)
        columns[n][j] = t.input_history_.col(wrap(head - j, Kernel)).data();
      z[n].noalias() = t.weights_.input_bias + t.weights_.input_projection * t.last_input_;
      t.heads_[0] = next(head, Kernel);
    }
    add_taps_together<G>(
        z, nets, columns, [](const Tcn& t) -> const auto& { return t.weights_.input_taps; });
    for (std::size_t n = 0; n < G; ++n)
      nets[n].hidden_ = z[n].cwiseMax(S(0));

    for (int l = 1; l < Levels; ++l) {
      const int length = Shape::history_length(l);
      const int dilation = Shape::dilation(l);
      for (std::size_t n = 0; n < G; ++n) {
        Tcn& t = nets[n];
        const int head = t.heads_[l];
        t.history_column(l, head) = t.hidden_;
        for (int j = 0; j < Kernel; ++j)
          columns[n][j] = t.history_column(l, wrap(head - j * dilation, length)).data();
        z[n] = t.weights_.bias[l - 1] + t.hidden_;
        t.heads_[l] = next(head, length);
      }
      add_taps_together<G>(
          z, nets, columns, [l](const Tcn& t) -> const auto& { return t.weights_.taps[l - 1]; });
      for (std::size_t n = 0; n < G; ++n)
        nets[n].hidden_ = z[n].cwiseMax(S(0));
    }
    for (std::size_t n = 0; n < G; ++n)
      nets[n].apply_heads();
  }

  /// add_taps of G networks (network n: z[n] += Σ_j W_j·x_j with W = taps(nets[n]), x = x[n]),
  /// each in add_taps' order of operations. The per-tap form runs tap by tap: tap j's partial sum
  /// over the columns, then z += partial, is the same arithmetic as add_taps' K partial sums added
  /// to z in tap order, with one live accumulator per network instead of K.
  template <std::size_t G, typename Taps>
  static void add_taps_together(std::array<HiddenVector, G>& z, const Tcn* nets,
                                const std::array<std::array<const S*, Kernel>, G>& x,
                                Taps taps) noexcept {
    using Matrix = std::remove_cvref_t<decltype(taps(nets[0])[0])>;
    constexpr int columns = Matrix::ColsAtCompileTime;
    std::array<const Matrix*, G> w;
    if constexpr (kAccumulatorPerTap) {
      for (int j = 0; j < Kernel; ++j) {
        for_each<G>([&](auto n) { w[n] = &taps(nets[n])[j]; });
        std::array<HiddenVector, G> partial;
        for_each<G>([&](auto n) { partial[n].noalias() = w[n]->col(0) * x[n][j][0]; });
        for (int c = 1; c < columns; ++c)
          for_each<G>([&](auto n) { partial[n].noalias() += w[n]->col(c) * x[n][j][c]; });
        for_each<G>([&](auto n) { z[n] += partial[n]; });
      }
    } else {
      for (int j = 0; j < Kernel; ++j) {
        for_each<G>([&](auto n) { w[n] = &taps(nets[n])[j]; });
        for (int c = 0; c < columns; ++c)
          for_each<G>([&](auto n) { z[n].noalias() += w[n]->col(c) * x[n][j][c]; });
      }
    }
  }

  /// f(n) for n = 0 … G−1 as compile-time constants, unrolled: the networks' accumulators then
  /// stay in registers instead of an array in memory.
  template <std::size_t G, typename F>
  [[gnu::always_inline]] static void for_each(F&& f) noexcept {
    [&]<std::size_t... n>(std::index_sequence<n...>) {
      (f(std::integral_constant<std::size_t, n>{}), ...);
    }
    (std::make_index_sequence<G>{});
  }

  void apply_heads() noexcept {
    low_.noalias() = weights_.low_bias + weights_.low_weight * hidden_;
    high_.noalias() = weights_.high_bias + weights_.high_weight * hidden_;
    output_ = low_ + high_;
  }

  void clear_history() noexcept {
    last_input_.setZero();
    input_history_.setZero();
    hidden_history_.fill(S(0));
    pending_.fill(S(0));
    heads_.fill(0);
    hidden_.setZero();
    low_.setZero();
    high_.setZero();
    output_.setZero();
  }

  static constexpr std::array<int, Levels + 1> kHiddenOffsets = Shape::hidden_history_offsets();
  static constexpr std::array<int, Levels + 1> kPendingOffsets = Shape::pending_offsets();

  Weights weights_;
  /// With BFloat16Weights: tap j of block l ≥ 1 at ((l − 1)·Kernel + j)·Hidden²/2, column pair p
  /// (columns 2p, 2p + 1) of its rows r at p·Hidden + r (store_hidden_taps); empty otherwise.
  alignas(64) std::array<HiddenTap, kBFloat16 ? (Levels - 1) * Kernel * Hidden * Hidden / 2
                                              : 0> paired_taps_{};
  Eigen::Matrix<S, In, Kernel> input_history_;  ///< ring of the raw inputs (block 0, d = 1)
  /// Rings of blocks 1 … Levels−1, Hidden × ((K − 1)·d_l + 1) each, column-major, back to back.
  alignas(64) std::array<S, Hidden * Shape::hidden_history_columns> hidden_history_{};
  /// Every block's pending sums for the x86 kernels, Hidden × ((K − 1)·d_l + 1) each (see
  /// rebuild_pending).
  alignas(64) std::array<S, Hidden * Shape::pending_columns> pending_{};
  std::array<int, Levels> heads_{};  ///< next column to write in each ring
  Input last_input_;                 ///< last finite input, stands in for a non-finite one
  long skipped_inputs_ = 0;
  HiddenVector hidden_;
  Output low_;
  Output high_;
  Output output_;
  TcnKernel kernel_ = preferred_tcn_kernel<S, Hidden>();
};

}  // namespace tpf
