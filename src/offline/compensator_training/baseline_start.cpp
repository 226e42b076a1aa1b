#include "offline/compensator_training/baseline_start.hpp"

#include "tpf/common/error.hpp"

namespace tpf::offline {

TcnParameters baseline_start(const TcnArchitecture& a, std::uint64_t seed,
                             const Eigen::VectorXd& input_mean, const Eigen::VectorXd& input_std,
                             const Eigen::VectorXi& baseline_input) {
  const int outputs = a.outputs;
  if (a.hidden < 2 * outputs || baseline_input.size() != outputs || input_mean.size() != a.inputs ||
      input_std.size() != a.inputs)
    throw Error::at("baseline start", 0, "architecture",
                    "needs hidden ≥ 2·outputs and one baseline input per output");
  TcnParameters p = init_tcn_parameters(a, seed);
  if (p.blocks.empty() || p.blocks[0].projection.size() == 0)
    throw Error::at("baseline start", 0, "architecture",
                    "block 0 needs an input projection (inputs ≠ hidden)");
  p.input_mean = input_mean;
  p.input_std = input_std;
  for (int o = 0; o < outputs; ++o) {
    const int c = baseline_input[o];
    for (int sign = 0; sign < 2; ++sign) {
      const int unit = 2 * o + sign;  // the first 2·outputs channels carry the baselines
      for (std::size_t l = 0; l < p.blocks.size(); ++l) {
        TcnBlockParameters& b = p.blocks[l];
        for (auto& w : b.taps)
          w.row(unit).setZero();
        b.bias[unit] = 0.0;
        if (l == 0) {
          b.projection.row(unit).setZero();
          b.projection(unit, c) = sign == 0 ? 1.0 : -1.0;
        }
      }
      p.low_weight.col(unit).setZero();
      p.high_weight.col(unit).setZero();
    }
  }
  for (int o = 0; o < outputs; ++o) {
    const int c = baseline_input[o];
    const double gain = input_std[c];
    p.low_weight(o, 2 * o) = gain;
    p.low_weight(o, 2 * o + 1) = -gain;
    p.low_bias[o] = input_mean[c];
    p.high_bias[o] = 0.0;
  }
  return p;
}

}  // namespace tpf::offline
