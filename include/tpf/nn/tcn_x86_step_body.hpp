// The body of one x86 TCN step kernel, included once per register width by
// tcn_x86_kernels.hpp with these names defined (no include guard: it is meant to be included
// twice; it undefines them at its end):
//   TPF_TCN_INLINE     the helpers' attributes (target, always_inline)
//   TPF_TCN_TARGET     the step's target string             TPF_TCN_BYTES  register width, bytes
//   TPF_TCN_REGISTERS  vector registers of the width (16 or 32)
//   TPF_TCN_LOAD, TPF_TCN_SPLAT                             the width's load and broadcast
//   TPF_TCN_WEIGHTS    the width's load of a tap's columns (weights256, weights512)
//   TPF_TCN_LANE_BROADCAST  1: the lagged taps' inputs are broadcast from registers (a lane
//                      permute), 0: from memory (the ring column)
//   TPF_TCN_SUM, TPF_TCN_NOW, TPF_TCN_LATER, TPF_TCN_LATER_ALL, TPF_TCN_STEP
//                      the names this body defines
// (A target attribute cannot depend on a template argument, and GCC 12 and clang 14 refuse a
// body shared through an always_inline function across targets, hence an included body.)

/// (acc_0 + acc_1) + (acc_2 + acc_3) of register r (A = 4), acc_0 + acc_1 (A = 2), acc_0.
template <int A, int R, typename Register>
TPF_TCN_INLINE Register TPF_TCN_SUM(Register (&acc)[A][R], int r) noexcept {
  if constexpr (A == 1)
    return acc[0][r];
  else if constexpr (A == 2)
    return add(acc[0][r], acc[1][r]);
  else
    return add(add(acc[0][r], acc[1][r]), add(acc[2][r], acc[3][r]));
}

/// z += W_0·x (+ P·x, block 0's projection) for the R registers of the hidden vector from
/// element `row` on, x a block's input at t (Columns values; W_0, P: Hidden × Columns), the
/// axpys dealt by column c to A sums (c mod A) with z in the first.
template <int A, int R, int Hidden, int Columns, bool Projection, typename S, typename Tap,
          typename Register>
TPF_TCN_INLINE void TPF_TCN_NOW(Register (&z)[R], const Tap* tap, const S* projection, const S* x,
                                int row) noexcept {
  constexpr int lanes = TPF_TCN_BYTES / int(sizeof(S));
  Register acc[A][R];
  TPF_TCN_UNROLL(8)
  for (int r = 0; r < R; ++r) {
    acc[0][r] = z[r];
    TPF_TCN_UNROLL(4)
    for (int a = 1; a < A; ++a)
      acc[a][r] = Register{};
  }
  // Columns `first` … first + step − 1 per pass: whole sums' rounds and whole loads.
  constexpr int G = tcn_x86::columns_per_load<Tap>(), step = A % G == 0 ? A : A * G;
  for (int first = 0; first < Columns; first += step) {
    Register w[R][G];
    TPF_TCN_UNROLL(8)
    for (int k = 0; k < step; ++k) {
      const int c = first + k, a = k % A;
      if (c >= Columns) break;
      if (k % G == 0) {
        TPF_TCN_UNROLL(8)
        for (int r = 0; r < R; ++r)
          TPF_TCN_WEIGHTS<Hidden>(tap, c, row + r * lanes, w[r]);
      }
      const Register s = TPF_TCN_SPLAT(x + c);
      TPF_TCN_UNROLL(8)
      for (int r = 0; r < R; ++r) {
        acc[a][r] = fmadd(w[r][k % G], s, acc[a][r]);
        if constexpr (Projection)
          acc[a][r] = fmadd(TPF_TCN_LOAD(projection + c * Hidden + row + r * lanes), s, acc[a][r]);
      }
    }
  }
  TPF_TCN_UNROLL(8)
  for (int r = 0; r < R; ++r)
    z[r] = TPF_TCN_SUM(acc, r);
}

/// pending[j] += W_j·x for 1 ≤ j < K (the pending sum of time t + j·d; j = K − 1 starts it), for
/// the R registers from element `row` on, each tap's axpys dealt by column c to B sums (c mod B);
/// each broadcast x_c serves the K − 1 taps. x is broadcast from `x_registers` (V registers) if
/// InRegisters and the width permutes lanes (TPF_TCN_LANE_BROADCAST; float taps), else loaded
/// from `x` (block 0's raw input, bfloat16 pairs, AVX2).
template <int B, int R, int K, int Hidden, int Columns, bool InRegisters, int V, typename S,
          typename Tap, typename Register>
TPF_TCN_INLINE void TPF_TCN_LATER(const Tap* const (&taps)[K], const S* x,
                                  const Register (&x_registers)[V], S* const (&pending)[K],
                                  int row) noexcept {
  constexpr int lanes = TPF_TCN_BYTES / int(sizeof(S));
  Register acc[K][B][R];
  TPF_TCN_UNROLL(8)
  for (int r = 0; r < R; ++r)
    TPF_TCN_UNROLL(16)
  for (int j = 1; j < K; ++j) {
    acc[j][0][r] = j == K - 1 ? Register{} : TPF_TCN_LOAD(pending[j] + row + r * lanes);
    TPF_TCN_UNROLL(4)
    for (int a = 1; a < B; ++a)
      acc[j][a][r] = Register{};
  }
  // Columns `first` … first + step − 1 per pass: whole sums' rounds and whole loads.
  constexpr int G = tcn_x86::columns_per_load<Tap>(), step = B % G == 0 ? B : B * G;
  for (int first = 0; first < Columns; first += step) {
    Register w[K][R][G];
    TPF_TCN_UNROLL(8)
    for (int k = 0; k < step; ++k) {
      const int c = first + k, a = k % B;
      if (c >= Columns) break;
      if (k % G == 0) {
        TPF_TCN_UNROLL(8)
        for (int r = 0; r < R; ++r)
          TPF_TCN_UNROLL(16)
        for (int j = 1; j < K; ++j)
          TPF_TCN_WEIGHTS<Hidden>(taps[j], c, row + r * lanes, w[j][r]);
      }
      Register s;
      if constexpr (InRegisters && G == 1 && TPF_TCN_LANE_BROADCAST)
        s = splat_lane(x_registers[c / lanes], c % lanes);
      else
        s = TPF_TCN_SPLAT(x + c);
      TPF_TCN_UNROLL(8)
      for (int r = 0; r < R; ++r)
        TPF_TCN_UNROLL(16)
      for (int j = 1; j < K; ++j)
        acc[j][a][r] = fmadd(w[j][r][k % G], s, acc[j][a][r]);
    }
  }
  TPF_TCN_UNROLL(8)
  for (int r = 0; r < R; ++r)
    TPF_TCN_UNROLL(16)
  for (int j = 1; j < K; ++j)
    store(pending[j] + row + r * lanes, TPF_TCN_SUM(acc[j], r));
}

/// pending[j] += W_j·x for the whole hidden vector (TPF_TCN_LATER by R registers at a time).
template <int R, int K, int Hidden, int Columns, bool InRegisters, int V, typename Tap, typename S,
          typename Register>
TPF_TCN_INLINE void TPF_TCN_LATER_ALL(const tcn_x86::BlockStep<Tap, S, K>& block,
                                      const Register (&x_registers)[V]) noexcept {
  constexpr int lanes = TPF_TCN_BYTES / int(sizeof(S)), B = tcn_x86::lagged_sums(R, K);
  TPF_TCN_UNROLL(8)
  for (int row = 0; row < Hidden; row += R * lanes)
    TPF_TCN_LATER<B, R, K, Hidden, Columns, InRegisters, V, S, Tap, Register>(
        block.taps, block.x, x_registers, block.pending, row);
}

/// Tcn::step in TPF_TCN_BYTES-byte registers (see tcn_x86_kernels.hpp). The hidden blocks' taps
/// are w.taps (HiddenTap = S, `paired` unused) or, HiddenTap = BFloat16Pair, `paired`: tap j of
/// block l ≥ 1 from paired + ((l − 1)·Kernel + j)·Hidden²/2 (Tcn::paired_taps_).
template <typename S, int In, int Hidden, int Levels, int Kernel, int Out, typename HiddenTap>
__attribute__((target(TPF_TCN_TARGET))) void TPF_TCN_STEP(
    const TcnWeights<S, In, Hidden, Levels, Kernel, Out>& w, const TcnStepBuffers<S>& b,
    const HiddenTap* paired) noexcept {
  using Shape = TcnShape<Levels, Kernel>;
  using Register = decltype(TPF_TCN_LOAD(static_cast<const S*>(nullptr)));
  constexpr int lanes = TPF_TCN_BYTES / int(sizeof(S)), V = Hidden / lanes,
                R = tcn_x86::row_registers(V, Kernel, TPF_TCN_REGISTERS),
                A = tcn_x86::current_sums(R);
  static_assert(Hidden % lanes == 0, "a hidden vector fills whole registers");
  constexpr std::array<int, Levels + 1> rings = Shape::hidden_history_offsets(),
                                        pendings = Shape::pending_offsets();
  // h: the current block's input; lagged_input: the input of the block whose lagged taps are
  // still to add (broadcast from registers where TPF_TCN_LANE_BROADCAST, else unused).
  Register h[V], lagged_input[V];

  // Block 0: z = b + pending(t) + P·x(t) + W_0·x(t), h = ReLU(z).
  tcn_x86::BlockStep<S, S, Kernel> block;
  for (int j = 0; j < Kernel; ++j) {
    block.taps[j] = w.input_taps[j].data();
    block.pending[j] = b.pending + Hidden * tcn_x86::wrap(b.input_head + j, Kernel);
  }
  block.x = b.input_history + In * b.input_head;
  TPF_TCN_UNROLL(8)
  for (int row = 0; row < Hidden; row += R * lanes) {
    Register z[R];
    TPF_TCN_UNROLL(8)
    for (int r = 0; r < R; ++r)
      z[r] = add(TPF_TCN_LOAD(w.input_bias.data() + row + r * lanes),
                 TPF_TCN_LOAD(block.pending[0] + row + r * lanes));
    TPF_TCN_NOW<A, R, Hidden, In, true>(z, block.taps[0], w.input_projection.data(), block.x, row);
    TPF_TCN_UNROLL(8)
    for (int r = 0; r < R; ++r)
      h[row / lanes + r] = relu(z[r]);
  }

  // Block l ≥ 1: z = b_l + h + pending(t) + W_{l,0}·h, h = h_{l−1}(t) also written to block
  // l's ring (the portable path's history). Then the previous block's lagged taps:
  // pending(t + j·d) += W_j·x(t); they wait on nothing that follows, so they come after what
  // does in the instruction stream and fill the vector unit while it waits. `block` stays block
  // 0's (its taps are S), `hidden_block` is block l − 1 ≥ 1's.
  tcn_x86::BlockStep<HiddenTap, S, Kernel> hidden_block{};
  TPF_TCN_UNROLL(16)
  for (int l = 1; l < Levels; ++l) {
    const int length = Shape::history_length(l), dilation = Shape::dilation(l);
    tcn_x86::BlockStep<HiddenTap, S, Kernel> next;
    for (int j = 0; j < Kernel; ++j) {
      if constexpr (std::is_same_v<HiddenTap, S>)
        next.taps[j] = w.taps[l - 1][j].data();
      else
        next.taps[j] = paired + ((l - 1) * Kernel + j) * (Hidden * Hidden / 2);
      next.pending[j] =
          b.pending + Hidden * (pendings[l] + tcn_x86::wrap(b.heads[l] + j * dilation, length));
    }
    S* const current = b.hidden_history + Hidden * (rings[l] + b.heads[l]);
    next.x = current;
    TPF_TCN_UNROLL(8)
    for (int v = 0; v < V; ++v)
      store(current + v * lanes, h[v]);
    Register out[V];
    TPF_TCN_UNROLL(8)
    for (int row = 0; row < Hidden; row += R * lanes) {
      Register z[R];
      TPF_TCN_UNROLL(8)
      for (int r = 0; r < R; ++r)
        z[r] = add(add(TPF_TCN_LOAD(w.bias[l - 1].data() + row + r * lanes), h[row / lanes + r]),
                   TPF_TCN_LOAD(next.pending[0] + row + r * lanes));
      TPF_TCN_NOW<A, R, Hidden, Hidden, false>(z, next.taps[0], static_cast<const S*>(nullptr),
                                               current, row);
      TPF_TCN_UNROLL(8)
      for (int r = 0; r < R; ++r)
        out[row / lanes + r] = relu(z[r]);
    }
    if (l == 1)
      TPF_TCN_LATER_ALL<R, Kernel, Hidden, In, false>(block, h);
    else
      TPF_TCN_LATER_ALL<R, Kernel, Hidden, Hidden, true>(hidden_block, lagged_input);
    TPF_TCN_UNROLL(8)
    for (int v = 0; v < V; ++v) {
      lagged_input[v] = h[v];
      h[v] = out[v];
    }
    hidden_block = next;
  }

  TPF_TCN_UNROLL(8)
  for (int v = 0; v < V; ++v)
    store(b.hidden + v * lanes, h[v]);
  if constexpr (Out == 1) {
    Register low = Register{}, high = Register{};
    TPF_TCN_UNROLL(8)
    for (int v = 0; v < V; ++v) {
      low = fmadd(TPF_TCN_LOAD(w.low_weight.data() + v * lanes), h[v], low);
      high = fmadd(TPF_TCN_LOAD(w.high_weight.data() + v * lanes), h[v], high);
    }
    *b.low = w.low_bias[0] + lane_sum(low);
    *b.high = w.high_bias[0] + lane_sum(high);
  }
  if constexpr (Levels == 1)
    TPF_TCN_LATER_ALL<R, Kernel, Hidden, In, false>(block, lagged_input);
  else
    TPF_TCN_LATER_ALL<R, Kernel, Hidden, Hidden, true>(hidden_block, lagged_input);
}

// This width's parameters end here; the next inclusion defines its own.
#undef TPF_TCN_INLINE
#undef TPF_TCN_TARGET
#undef TPF_TCN_BYTES
#undef TPF_TCN_LOAD
#undef TPF_TCN_WEIGHTS
#undef TPF_TCN_LANE_BROADCAST
#undef TPF_TCN_SPLAT
#undef TPF_TCN_SUM
#undef TPF_TCN_NOW
#undef TPF_TCN_LATER
#undef TPF_TCN_LATER_ALL
#undef TPF_TCN_REGISTERS
#undef TPF_TCN_STEP
