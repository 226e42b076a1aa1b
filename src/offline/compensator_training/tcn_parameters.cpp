#include "offline/compensator_training/tcn_parameters.hpp"

#include <cmath>
#include <random>

namespace tpf::offline {

TcnParameters zero_tcn_parameters(const TcnArchitecture& a) {
  TcnParameters p;
  p.architecture = a;
  p.input_mean = Eigen::VectorXd::Zero(a.inputs);
  p.input_std = Eigen::VectorXd::Ones(a.inputs);
  p.blocks.resize(a.levels);
  for (int l = 0; l < a.levels; ++l) {
    TcnBlockParameters& b = p.blocks[l];
    const int in = a.block_inputs(l);
    b.taps.assign(a.kernel, Eigen::MatrixXd::Zero(a.hidden, in));
    b.bias = Eigen::VectorXd::Zero(a.hidden);
    if (in != a.hidden) b.projection = Eigen::MatrixXd::Zero(a.hidden, in);
  }
  p.low_weight = Eigen::MatrixXd::Zero(a.outputs, a.hidden);
  p.high_weight = Eigen::MatrixXd::Zero(a.outputs, a.hidden);
  p.low_bias = Eigen::VectorXd::Zero(a.outputs);
  p.high_bias = Eigen::VectorXd::Zero(a.outputs);
  return p;
}

TcnParameters init_tcn_parameters(const TcnArchitecture& a, std::uint64_t seed) {
  TcnParameters p = zero_tcn_parameters(a);
  std::mt19937_64 rng(seed);
  auto fill = [&rng](Eigen::MatrixXd& m, double bound) {
    std::uniform_real_distribution<double> u(-bound, bound);
    for (Eigen::Index i = 0; i < m.size(); ++i)
      m.data()[i] = u(rng);
  };
  for (int l = 0; l < a.levels; ++l) {
    const int in = a.block_inputs(l);
    for (auto& w : p.blocks[l].taps)
      fill(w, std::sqrt(6.0 / (a.kernel * in)));
    if (p.blocks[l].projection.size() > 0) fill(p.blocks[l].projection, std::sqrt(6.0 / in));
  }
  fill(p.low_weight, 0.1 * std::sqrt(1.0 / a.hidden));
  fill(p.high_weight, 0.1 * std::sqrt(1.0 / a.hidden));
  return p;
}

void for_each_tcn_tensor(
    TcnParameters& p, const std::function<void(const std::string&, double*, Eigen::Index)>& visit) {
  for (std::size_t l = 0; l < p.blocks.size(); ++l) {
    TcnBlockParameters& b = p.blocks[l];
    const std::string prefix = "blocks." + std::to_string(l);
    for (std::size_t j = 0; j < b.taps.size(); ++j) {
      visit(prefix + ".conv.weight[lag " + std::to_string(j) + "]", b.taps[j].data(),
            b.taps[j].size());
    }
    visit(prefix + ".conv.bias", b.bias.data(), b.bias.size());
    if (b.projection.size() > 0)
      visit(prefix + ".downsample.weight", b.projection.data(), b.projection.size());
  }
  visit("head_low.weight", p.low_weight.data(), p.low_weight.size());
  visit("head_low.bias", p.low_bias.data(), p.low_bias.size());
  visit("head_high.weight", p.high_weight.data(), p.high_weight.size());
  visit("head_high.bias", p.high_bias.data(), p.high_bias.size());
}

Eigen::Index tcn_parameter_count(const TcnArchitecture& a) {
  Eigen::Index n = 0;
  for (int l = 0; l < a.levels; ++l) {
    const int in = a.block_inputs(l);
    n += static_cast<Eigen::Index>(a.kernel) * a.hidden * in + a.hidden;
    if (in != a.hidden) n += static_cast<Eigen::Index>(a.hidden) * in;
  }
  return n + 2 * (static_cast<Eigen::Index>(a.outputs) * a.hidden + a.outputs);
}

Eigen::VectorXd flatten(TcnParameters& p) {
  Eigen::VectorXd flat(tcn_parameter_count(p.architecture));
  Eigen::Index at = 0;
  for_each_tcn_tensor(p, [&](const std::string&, double* values, Eigen::Index size) {
    flat.segment(at, size) = Eigen::Map<const Eigen::VectorXd>(values, size);
    at += size;
  });
  return flat;
}

void unflatten(const Eigen::VectorXd& flat, TcnParameters& p) {
  Eigen::Index at = 0;
  for_each_tcn_tensor(p, [&](const std::string&, double* values, Eigen::Index size) {
    Eigen::Map<Eigen::VectorXd>(values, size) = flat.segment(at, size);
    at += size;
  });
}

namespace {

TcnTensor row_major(const Eigen::MatrixXd& m, std::vector<int> shape) {
  TcnTensor t{std::move(shape), {}};
  t.values.reserve(m.size());
  for (Eigen::Index r = 0; r < m.rows(); ++r)
    for (Eigen::Index c = 0; c < m.cols(); ++c)
      t.values.push_back(m(r, c));
  return t;
}

Eigen::MatrixXd from_row_major(const TcnTensor& t, int rows, int cols) {
  return Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
      t.values.data(), rows, cols);
}

}  // namespace

TcnWeightFile to_weight_file(const TcnParameters& p) {
  const TcnArchitecture& a = p.architecture;
  TcnWeightFile file;
  file.inputs = a.inputs;
  file.hidden = a.hidden;
  file.levels = a.levels;
  file.kernel = a.kernel;
  file.outputs = a.outputs;
  file.input_mean.assign(p.input_mean.data(), p.input_mean.data() + p.input_mean.size());
  file.input_std.assign(p.input_std.data(), p.input_std.data() + p.input_std.size());
  for (int l = 0; l < a.levels; ++l) {
    const TcnBlockParameters& b = p.blocks[l];
    const int in = a.block_inputs(l);
    TcnTensor conv{{a.hidden, in, a.kernel}, std::vector<double>(b.taps[0].size() * a.kernel)};
    for (int o = 0; o < a.hidden; ++o)
      for (int i = 0; i < in; ++i)
        for (int k = 0; k < a.kernel; ++k)
          conv.values[(o * in + i) * a.kernel + k] = b.taps[a.kernel - 1 - k](o, i);
    file.tensors[tcn_conv_weight_name(l)] = std::move(conv);
    file.tensors[tcn_conv_bias_name(l)] = row_major(b.bias, {a.hidden});
    if (b.projection.size() > 0) {
      file.tensors[tcn_downsample_name()] = row_major(b.projection, {a.hidden, in, 1});
    }
  }
  file.tensors[tcn_head_weight_name(false)] = row_major(p.low_weight, {a.outputs, a.hidden});
  file.tensors[tcn_head_bias_name(false)] = row_major(p.low_bias, {a.outputs});
  file.tensors[tcn_head_weight_name(true)] = row_major(p.high_weight, {a.outputs, a.hidden});
  file.tensors[tcn_head_bias_name(true)] = row_major(p.high_bias, {a.outputs});
  return file;
}

TcnParameters from_weight_file(const TcnWeightFile& file) {
  const TcnArchitecture a{file.inputs, file.hidden, file.levels, file.kernel, file.outputs};
  TcnParameters p = zero_tcn_parameters(a);
  p.input_mean = Eigen::Map<const Eigen::VectorXd>(file.input_mean.data(), a.inputs);
  p.input_std = Eigen::Map<const Eigen::VectorXd>(file.input_std.data(), a.inputs);
  for (int l = 0; l < a.levels; ++l) {
    TcnBlockParameters& b = p.blocks[l];
    const int in = a.block_inputs(l);
    const TcnTensor& conv = file.tensor(tcn_conv_weight_name(l), {a.hidden, in, a.kernel});
    for (int o = 0; o < a.hidden; ++o)
      for (int i = 0; i < in; ++i)
        for (int k = 0; k < a.kernel; ++k)
          b.taps[a.kernel - 1 - k](o, i) = conv.values[(o * in + i) * a.kernel + k];
    b.bias = from_row_major(file.tensor(tcn_conv_bias_name(l), {a.hidden}), a.hidden, 1);
    if (in != a.hidden) {
      b.projection =
          from_row_major(file.tensor(tcn_downsample_name(), {a.hidden, in, 1}), a.hidden, in);
    }
  }
  p.low_weight = from_row_major(file.tensor(tcn_head_weight_name(false), {a.outputs, a.hidden}),
                                a.outputs, a.hidden);
  p.low_bias = from_row_major(file.tensor(tcn_head_bias_name(false), {a.outputs}), a.outputs, 1);
  p.high_weight = from_row_major(file.tensor(tcn_head_weight_name(true), {a.outputs, a.hidden}),
                                 a.outputs, a.hidden);
  p.high_bias = from_row_major(file.tensor(tcn_head_bias_name(true), {a.outputs}), a.outputs, 1);
  return p;
}

}  // namespace tpf::offline
