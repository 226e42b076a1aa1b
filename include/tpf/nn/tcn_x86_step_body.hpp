// The body of one x86 TCN step kernel, included once per register width by
// tcn_x86_kernels.hpp with these names defined (no include guard: it is meant to be included
// twice):
//   TPF_TCN_INLINE  the helpers' attributes (target, always_inline)
//   TPF_TCN_TARGET  the step's target string            TPF_TCN_BYTES  register width, bytes
//   TPF_TCN_LOAD, TPF_TCN_SPLAT                          the width's load and broadcast
//   TPF_TCN_SUM, TPF_TCN_AXPYS, TPF_TCN_STEP             the names this body defines
// (A target attribute cannot depend on a template argument, and GCC 12 and clang 14 refuse a
// body shared through an always_inline function across targets, hence an included body.)

/// (acc_0 + acc_1) + (acc_2 + acc_3) of register v (A = 4), acc_0 + acc_1 (A = 2), acc_0.
template <int A, int V, typename Register>
TPF_TCN_INLINE Register TPF_TCN_SUM(Register (&acc)[A][V], int v) noexcept {
  if constexpr (A == 1)
    return acc[0][v];
  else if constexpr (A == 2)
    return add(acc[0][v], acc[1][v]);
  else
    return add(add(acc[0][v], acc[1][v]), add(acc[2][v], acc[3][v]));
}

/// acc[c mod A] += W[:, c]·x[c] for c < Columns (W: V registers × Columns, column-major).
template <int A, int V, int Columns, typename S, typename Register>
TPF_TCN_INLINE void TPF_TCN_AXPYS(Register (&acc)[A][V], const S* W, const S* x) noexcept {
  constexpr int lanes = TPF_TCN_BYTES / int(sizeof(S));
  for (int first = 0; first < Columns; first += A) {
#pragma GCC unroll 4
    for (int a = 0; a < A; ++a) {
      if (first + a >= Columns) break;
      const S* column = W + (first + a) * V * lanes;
      const Register s = TPF_TCN_SPLAT(x + first + a);
#pragma GCC unroll 8
      for (int v = 0; v < V; ++v)
        acc[a][v] = fmadd(TPF_TCN_LOAD(column + v * lanes), s, acc[a][v]);
    }
  }
}

/// Tcn::step in TPF_TCN_BYTES-byte registers (see tcn_x86_kernels.hpp).
template <typename S, int In, int Hidden, int Levels, int Kernel, int Out>
__attribute__((target(TPF_TCN_TARGET))) void TPF_TCN_STEP(
    const TcnWeights<S, In, Hidden, Levels, Kernel, Out>& w, const TcnStepBuffers<S>& b) noexcept {
  using Shape = TcnShape<Levels, Kernel>;
  using Register = decltype(TPF_TCN_LOAD(static_cast<const S*>(nullptr)));
  constexpr int lanes = TPF_TCN_BYTES / int(sizeof(S)), V = Hidden / lanes,
                A = V == 1   ? 4
                    : V == 2 ? 2
                             : 1;
  static_assert(Hidden % lanes == 0, "a hidden vector fills whole registers");
  constexpr std::array<int, Levels + 1> offsets = Shape::hidden_history_offsets();
  Register acc[A][V], h[V];

  // Block 0: z = b + P·x(t) + Σ_j W_j·x(t − j).
#pragma GCC unroll 8
  for (int v = 0; v < V; ++v) {
    acc[0][v] = TPF_TCN_LOAD(w.input_bias.data() + v * lanes);
#pragma GCC unroll 4
    for (int a = 1; a < A; ++a)
      acc[a][v] = Register{};
  }
  for (int j = Kernel - 1; j >= 0; --j) {
    const int column = b.input_head - j < 0 ? b.input_head - j + Kernel : b.input_head - j;
    TPF_TCN_AXPYS<A, V, In>(acc, w.input_taps[j].data(), b.input_history + In * column);
  }
  TPF_TCN_AXPYS<A, V, In>(acc, w.input_projection.data(), b.input_history + In * b.input_head);
#pragma GCC unroll 8
  for (int v = 0; v < V; ++v)
    h[v] = relu(TPF_TCN_SUM(acc, v));

  // Blocks 1 … L−1: z = b_l + h + Σ_j W_{l,j}·h(t − j·d_l), the ring holding h's past.
  for (int l = 1; l < Levels; ++l) {
    const int length = Shape::history_length(l), dilation = Shape::dilation(l);
    S* const ring = b.hidden_history + Hidden * offsets[l];
    S* const current = ring + Hidden * b.heads[l];
#pragma GCC unroll 8
    for (int v = 0; v < V; ++v) {
      store(current + v * lanes, h[v]);
      acc[0][v] = add(TPF_TCN_LOAD(w.bias[l - 1].data() + v * lanes), h[v]);
#pragma GCC unroll 4
      for (int a = 1; a < A; ++a)
        acc[a][v] = Register{};
    }
    for (int j = Kernel - 1; j > 0; --j) {
      const int lagged = b.heads[l] - j * dilation;
      const S* x = ring + Hidden * (lagged < 0 ? lagged + length : lagged);
      TPF_TCN_AXPYS<A, V, Hidden>(acc, w.taps[l - 1][j].data(), x);
    }
    TPF_TCN_AXPYS<A, V, Hidden>(acc, w.taps[l - 1][0].data(), current);
#pragma GCC unroll 8
    for (int v = 0; v < V; ++v)
      h[v] = relu(TPF_TCN_SUM(acc, v));
  }

#pragma GCC unroll 8
  for (int v = 0; v < V; ++v)
    store(b.hidden + v * lanes, h[v]);
  if constexpr (Out == 1) {
    Register low = Register{}, high = Register{};
#pragma GCC unroll 8
    for (int v = 0; v < V; ++v) {
      low = fmadd(TPF_TCN_LOAD(w.low_weight.data() + v * lanes), h[v], low);
      high = fmadd(TPF_TCN_LOAD(w.high_weight.data() + v * lanes), h[v], high);
    }
    *b.low = w.low_bias[0] + lane_sum(low);
    *b.high = w.high_bias[0] + lane_sum(high);
  }
}
