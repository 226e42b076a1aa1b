#include "offline/train/tcn_window_model.hpp"

namespace tpf::offline {

void tcn_window_forward(const TcnParameters& p, const Eigen::Ref<const Eigen::MatrixXd>& inputs,
                        TcnWindowWorkspace& ws) {
  const TcnArchitecture& a = p.architecture;
  ws.activations.resize(a.levels + 1);
  ws.activations[0] = inputs;
  for (int l = 0; l < a.levels; ++l) {
    const TcnBlockParameters& b = p.blocks[l];
    const Eigen::MatrixXd& x = ws.activations[l];
    const int d = a.dilation(l);
    const Eigen::Index t_out = x.cols() - (a.kernel - 1) * d;
    Eigen::MatrixXd& z = ws.activations[l + 1];
    if (b.projection.size() > 0) {
      z.noalias() = b.projection * x.rightCols(t_out);
    } else {
      z = x.rightCols(t_out);
    }
    z.colwise() += b.bias;
    for (int j = 0; j < a.kernel; ++j) {
      z.noalias() += b.taps[j] * x.middleCols((a.kernel - 1 - j) * d, t_out);
    }
    z = z.cwiseMax(0.0);
  }
  const Eigen::MatrixXd& last = ws.activations[a.levels];
  ws.low.noalias() = p.low_weight * last;
  ws.low.colwise() += p.low_bias;
  ws.high.noalias() = p.high_weight * last;
  ws.high.colwise() += p.high_bias;
}

double tcn_window_loss(const TcnParameters& p, const Eigen::Ref<const Eigen::MatrixXd>& inputs,
                       const Eigen::Ref<const Eigen::MatrixXd>& target_low,
                       const Eigen::Ref<const Eigen::MatrixXd>& target_high, double weight_low,
                       double weight_high, TcnWindowWorkspace& ws, TcnParameters* gradient) {
  tcn_window_forward(p, inputs, ws);
  // Residuals become ∂L/∂low and ∂L/∂high in place.
  ws.low -= target_low;
  ws.high -= target_high;
  const double loss = weight_low * ws.low.squaredNorm() + weight_high * ws.high.squaredNorm();
  if (gradient == nullptr) return loss;
  ws.low *= 2.0 * weight_low;
  ws.high *= 2.0 * weight_high;

  const TcnArchitecture& a = p.architecture;
  TcnParameters& g = *gradient;
  const Eigen::MatrixXd& last = ws.activations[a.levels];
  g.low_weight.noalias() += ws.low * last.transpose();
  g.low_bias += ws.low.rowwise().sum();
  g.high_weight.noalias() += ws.high * last.transpose();
  g.high_bias += ws.high.rowwise().sum();
  ws.upstream.noalias() = p.low_weight.transpose() * ws.low;
  ws.upstream.noalias() += p.high_weight.transpose() * ws.high;

  for (int l = a.levels - 1; l >= 0; --l) {
    const TcnBlockParameters& b = p.blocks[l];
    TcnBlockParameters& gb = g.blocks[l];
    const Eigen::MatrixXd& x = ws.activations[l];
    const int d = a.dilation(l);
    const Eigen::Index t_out = ws.upstream.cols();
    // ∂L/∂z = ∂L/∂y ⊙ [y > 0].
    ws.upstream = (ws.activations[l + 1].array() > 0.0).select(ws.upstream, 0.0);
    const Eigen::MatrixXd& dz = ws.upstream;
    gb.bias += dz.rowwise().sum();
    for (int j = 0; j < a.kernel; ++j) {
      gb.taps[j].noalias() += dz * x.middleCols((a.kernel - 1 - j) * d, t_out).transpose();
    }
    if (b.projection.size() > 0) gb.projection.noalias() += dz * x.rightCols(t_out).transpose();
    if (l == 0) break;

    ws.downstream.setZero(x.rows(), x.cols());
    for (int j = 0; j < a.kernel; ++j) {
      ws.downstream.middleCols((a.kernel - 1 - j) * d, t_out).noalias() +=
          b.taps[j].transpose() * dz;
    }
    if (b.projection.size() > 0) {
      ws.downstream.rightCols(t_out).noalias() += b.projection.transpose() * dz;
    } else {
      ws.downstream.rightCols(t_out) += dz;
    }
    ws.upstream.swap(ws.downstream);
  }
  return loss;
}

}  // namespace tpf::offline
