#include "offline/compensator_training/tcn_window_model.hpp"

#include <algorithm>
#include <vector>

#include "offline/compensator_training/float_gemm16.hpp"

namespace tpf::offline {
namespace {

/// Whether block `level`'s products go through float_gemm16 (float, 16 output channels, K·C_in a
/// multiple of 4, AVX2): the same sums in the same order as Eigen's GEMM, in wider registers, read
/// from the block input's lagged columns instead of a stacked copy. Not for a single time step,
/// where Eigen takes its matrix–vector path instead. Forward and backward decide alike.
template <typename S>
bool use_float_gemm16(const TcnArchitecture& a, int level, Eigen::Index steps) {
  if constexpr (std::is_same_v<S, float>) {
    return a.hidden == 16 && (a.kernel * a.block_inputs(level)) % 4 == 0 && steps >= 2 &&
           float_gemm16_available();
  } else {
    return false;
  }
}

/// Row i = j·C_in + c of block `level`'s stacked input is x(c, t + (K − 1 − j)·d): its offset in
/// x's storage from column t (float_gemm16's B(i, t) = x[t·C_in + offset[i]]).
std::vector<std::ptrdiff_t>& lagged_offsets(const TcnArchitecture& a, int level,
                                            std::vector<std::ptrdiff_t>& offsets) {
  const std::ptrdiff_t in = a.block_inputs(level), d = a.dilation(level);
  offsets.resize(static_cast<std::size_t>(a.kernel * in));
  for (int j = 0; j < a.kernel; ++j)
    for (std::ptrdiff_t c = 0; c < in; ++c)
      offsets[static_cast<std::size_t>(j * in + c)] = (a.kernel - 1 - j) * d * in + c;
  return offsets;
}

/// Whether float_gemm16's reads of B(i, t) = b[t·stride + offset[i]], t < n, stay inside b's
/// `size` elements. The kernels are not instrumented in the sanitized build (src/offline/
/// CMakeLists.txt): each call's range is checked here, with the shapes of its other operands.
[[maybe_unused]] bool lagged_reads_fit(const std::vector<std::ptrdiff_t>& offsets,
                                       std::ptrdiff_t stride, Eigen::Index n, Eigen::Index size) {
  if (offsets.empty() || n < 1) return false;
  const std::ptrdiff_t top = *std::max_element(offsets.begin(), offsets.end());
  const std::ptrdiff_t low = *std::min_element(offsets.begin(), offsets.end());
  return low >= 0 && (n - 1) * stride + top < size;
}

/// [W_0 … W_{K−1}] of block `b` into `out` (C_out × K·C_in).
template <typename S, typename Matrix>
void stack_taps(const BasicTcnBlockParameters<S>& b, Matrix& out) {
  const Eigen::Index in = b.taps[0].cols();
  out.resize(b.taps[0].rows(), in * static_cast<Eigen::Index>(b.taps.size()));
  for (std::size_t j = 0; j < b.taps.size(); ++j)
    out.middleCols(j * in, in) = b.taps[j];
}

}  // namespace

template <typename S>
void tcn_window_forward(const BasicTcnParameters<S>& p, const TcnWindowMatrix<S>& inputs,
                        BasicTcnWindowWorkspace<S>& ws) {
  const TcnArchitecture& a = p.architecture;
  const auto levels = static_cast<std::size_t>(a.levels);
  ws.activations.resize(levels + 1);
  ws.stacked_inputs.resize(levels);
  ws.stacked_weights.resize(levels);
  ws.activations[0] = inputs;
  for (int l = 0; l < a.levels; ++l) {
    const BasicTcnBlockParameters<S>& b = p.blocks[l];
    const auto& x = ws.activations[l];
    const int d = a.dilation(l);
    const Eigen::Index in = x.rows(), t_out = x.cols() - (a.kernel - 1) * d;
    const bool avx2 = use_float_gemm16<S>(a, l, t_out);
    auto& stack = ws.stacked_inputs[l];
    if (!avx2) {
      stack.resize(a.kernel * in, t_out);
      for (int j = 0; j < a.kernel; ++j) {
        stack.middleRows(j * in, in) = x.middleCols((a.kernel - 1 - j) * d, t_out);
      }
    }
    auto& z = ws.activations[l + 1];
    if (b.projection.size() > 0) {
      z.noalias() = b.projection * x.rightCols(t_out);
    } else {
      z = x.rightCols(t_out);
    }
    z.colwise() += b.bias;
    auto& weights = ws.stacked_weights[l];
    stack_taps(b, weights);
    if (avx2) {
      if constexpr (std::is_same_v<S, float>) {
        lagged_offsets(a, l, ws.offsets);
        eigen_assert(weights.rows() == 16 && weights.cols() == a.kernel * in && z.rows() == 16 &&
                     z.cols() == t_out && lagged_reads_fit(ws.offsets, in, t_out, x.size()));
        float_gemm16_accumulate(weights.data(), a.kernel * in, x.data(), ws.offsets.data(), in,
                                t_out, z.data());
      }
    } else {
      z.noalias() += weights * stack;
    }
    z = z.cwiseMax(S(0));
  }
  const auto& last = ws.activations[a.levels];
  ws.low.noalias() = p.low_weight * last;
  ws.low.colwise() += p.low_bias;
  ws.high.noalias() = p.high_weight * last;
  ws.high.colwise() += p.high_bias;
}

template <typename S>
double tcn_window_loss(const BasicTcnParameters<S>& p, const TcnWindowMatrix<S>& inputs,
                       const TcnWindowMatrix<S>& target_low, const TcnWindowMatrix<S>& target_high,
                       double weight_low, double weight_high, BasicTcnWindowWorkspace<S>& ws,
                       std::type_identity_t<BasicTcnParameters<S>>* gradient,
                       const TcnWindowMatrix<S>* sample_scale) {
  tcn_window_forward(p, inputs, ws);
  // Scaled residuals s⊙(y − target) become ∂L/∂low and ∂L/∂high in place (times 2·w·s).
  ws.low -= target_low;
  ws.high -= target_high;
  if (sample_scale != nullptr) {
    ws.low.array() *= sample_scale->array();
    ws.high.array() *= sample_scale->array();
  }
  const double loss = weight_low * static_cast<double>(ws.low.squaredNorm()) +
                      weight_high * static_cast<double>(ws.high.squaredNorm());
  if (gradient == nullptr) return loss;
  ws.low *= static_cast<S>(2.0 * weight_low);
  ws.high *= static_cast<S>(2.0 * weight_high);
  if (sample_scale != nullptr) {
    ws.low.array() *= sample_scale->array();
    ws.high.array() *= sample_scale->array();
  }

  const TcnArchitecture& a = p.architecture;
  BasicTcnParameters<S>& g = *gradient;
  const auto& last = ws.activations[a.levels];
  g.low_weight.noalias() += ws.low * last.transpose();
  g.low_bias += ws.low.rowwise().sum();
  g.high_weight.noalias() += ws.high * last.transpose();
  g.high_bias += ws.high.rowwise().sum();
  const auto levels = static_cast<std::size_t>(a.levels);
  ws.input_gradients.resize(levels + 1);
  ws.weight_gradients.resize(levels);
  ws.stack_gradients.resize(levels);
  ws.transposed_weights.resize(levels);
  auto& top = ws.input_gradients[levels];
  top.noalias() = p.low_weight.transpose() * ws.low;
  top.noalias() += p.high_weight.transpose() * ws.high;

  for (int l = a.levels - 1; l >= 0; --l) {
    const BasicTcnBlockParameters<S>& b = p.blocks[l];
    BasicTcnBlockParameters<S>& gb = g.blocks[l];
    const auto& x = ws.activations[l];
    const int d = a.dilation(l);
    auto& upstream = ws.input_gradients[l + 1];
    const Eigen::Index t_out = upstream.cols();
    // ∂L/∂z = ∂L/∂y ⊙ [y > 0].
    const auto& y = ws.activations[l + 1];
    eigen_assert(y.rows() == upstream.rows() && y.cols() == upstream.cols());
    relu_gradient_mask(y.data(), upstream.data(), upstream.size());
    const auto& dz = upstream;
    gb.bias += dz.rowwise().sum();
    const Eigen::Index in = x.rows();
    const bool avx2 = use_float_gemm16<S>(a, l, t_out);
    auto& weight_gradient = ws.weight_gradients[l];
    if (avx2) {
      weight_gradient.resize(dz.rows(), a.kernel * in);
      if constexpr (std::is_same_v<S, float>) {
        lagged_offsets(a, l, ws.offsets);
        eigen_assert(dz.rows() == 16 && dz.cols() == t_out &&
                     lagged_reads_fit(ws.offsets, in, t_out, x.size()));
        float_gemm16_times_transpose(dz.data(), x.data(), ws.offsets.data(), in, a.kernel * in,
                                     t_out, weight_gradient.data());
      }
    } else {
      weight_gradient.noalias() = dz * ws.stacked_inputs[l].transpose();
    }
    for (int j = 0; j < a.kernel; ++j)
      gb.taps[j] += weight_gradient.middleCols(j * in, in);
    if (b.projection.size() > 0) gb.projection.noalias() += dz * x.rightCols(t_out).transpose();
    if (l == 0) break;

    const auto& weights = ws.stacked_weights[l];  // stacked by the forward pass
    auto& stack_gradient = ws.stack_gradients[l];
    if (avx2 && weights.cols() % 8 == 0) {
      auto& transposed = ws.transposed_weights[l];
      transposed = weights.transpose();
      stack_gradient.resize(weights.cols(), t_out);
      if constexpr (std::is_same_v<S, float>) {
        eigen_assert(transposed.cols() == 16 && dz.rows() == 16 && dz.cols() == t_out);
        float_gemm16_transpose_times(transposed.data(), weights.cols(), dz.data(), t_out,
                                     stack_gradient.data());
      }
    } else {
      stack_gradient.noalias() = weights.transpose() * dz;
    }
    auto& downstream = ws.input_gradients[l];
    downstream.setZero(x.rows(), x.cols());
    for (int j = 0; j < a.kernel; ++j) {
      downstream.middleCols((a.kernel - 1 - j) * d, t_out) += stack_gradient.middleRows(j * in, in);
    }
    if (b.projection.size() > 0) {
      downstream.rightCols(t_out).noalias() += b.projection.transpose() * dz;
    } else {
      downstream.rightCols(t_out) += dz;
    }
  }
  return loss;
}

template void tcn_window_forward(const BasicTcnParameters<double>&, const TcnWindowMatrix<double>&,
                                 BasicTcnWindowWorkspace<double>&);
template void tcn_window_forward(const BasicTcnParameters<float>&, const TcnWindowMatrix<float>&,
                                 BasicTcnWindowWorkspace<float>&);
template double tcn_window_loss(const BasicTcnParameters<double>&, const TcnWindowMatrix<double>&,
                                const TcnWindowMatrix<double>&, const TcnWindowMatrix<double>&,
                                double, double, BasicTcnWindowWorkspace<double>&,
                                BasicTcnParameters<double>*, const TcnWindowMatrix<double>*);
template double tcn_window_loss(const BasicTcnParameters<float>&, const TcnWindowMatrix<float>&,
                                const TcnWindowMatrix<float>&, const TcnWindowMatrix<float>&,
                                double, double, BasicTcnWindowWorkspace<float>&,
                                BasicTcnParameters<float>*, const TcnWindowMatrix<float>*);

}  // namespace tpf::offline
