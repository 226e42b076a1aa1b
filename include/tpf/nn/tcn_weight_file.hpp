// The TCN weight file: versioned JSON with the architecture, the input normalisation and the
// tensors by name. Written by the offline trainer, read by the core at start-up.
#pragma once

#include <array>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace tpf {

/// One named tensor: its shape and its values in row-major (C) order.
struct TcnTensor {
  std::vector<int> shape;
  std::vector<double> values;
};

/// Contents of a weight file, sizes at run time. Format (version 2: a compensator's torque
/// inputs and outputs in N·m; version 1, in the training log's effort unit, is refused):
///   { "format": "tpf-tcn-weights", "version": 2,
///     "architecture": { "inputs", "hidden", "levels", "kernel", "outputs",
///                       "activation": "relu", "dilations": [1, 2, …], "receptive_field" },
///     "normalisation": { "mean": [In], "std": [In] },      // x̃ = (x − mean)/std
///     "tensors": { "<name>": { "shape": [...], "values": [...] }, … } }
/// Tensor names and shapes (PyTorch Conv1d layout, kernel index k multiplies x(t − (K−1−k)·d)):
///   blocks.<l>.conv.weight [C_out, C_in, K], blocks.<l>.conv.bias [C_out],
///   blocks.0.downsample.weight [Hidden, In, 1] (only when In ≠ Hidden),
///   head_low.weight / head_high.weight [Out, Hidden], head_low.bias / head_high.bias [Out].
/// Optional, written by `tpf train`: "held_out": { "static": [Out], "static-to-kinetic": [Out],
/// "moving": [Out] }, per output the gain 1 − RMSE with the network / RMSE of the nominal residual
/// on data the network was not trained on (> 0: it helped), null where that regime had no data.
/// The weights act on the normalised input; the core folds the normalisation in when loading.
struct TcnWeightFile {
  static constexpr int kVersion = 2;

  std::string path;  ///< where it was read from or written to, for error messages
  int inputs = 0;
  int hidden = 0;
  int levels = 0;
  int kernel = 0;
  int outputs = 0;
  std::vector<double> input_mean;
  std::vector<double> input_std;
  std::map<std::string, TcnTensor> tensors;
  /// The regimes of held_out_gain, in its order.
  static constexpr std::array<const char*, 3> kHeldOutRegimes{"static", "static-to-kinetic",
                                                              "moving"};
  /// Held-out gain per regime (kHeldOutRegimes) and output; NaN: not scored. All empty: the file
  /// holds no held-out score (the network is used as it is).
  std::array<std::vector<double>, 3> held_out_gain;

  /// The tensor `name`, checked to have exactly `shape`; otherwise throws tpf::Error
  /// "<path>: tensors.<name>: shape [a, b] in the file, [c, d] expected" (or "missing").
  const TcnTensor& tensor(std::string_view name, const std::vector<int>& shape) const;

  /// Throws tpf::Error naming the first tensor of the file that is not in `expected_names`
  /// ("<path>: tensors.<name>: not a tensor of the compiled network").
  void refuse_unexpected_tensors(const std::vector<std::string>& expected_names) const;

  /// Throws tpf::Error naming the first hyperparameter that differs from the given ones
  /// (e.g. "<path>: architecture.hidden: 16 in the file, 32 expected").
  void require_architecture(int inputs, int hidden, int levels, int kernel, int outputs) const;
};

/// Tensor names of the format above.
std::string tcn_conv_weight_name(int block);
std::string tcn_conv_bias_name(int block);
std::string tcn_downsample_name();
std::string tcn_head_weight_name(bool high);
std::string tcn_head_bias_name(bool high);

/// Reads and validates a weight file (format, version, positive sizes, normalisation lengths and
/// std > 0, every tensor's value count equal to its shape's product, all values finite).
/// Throws tpf::Error naming the file and the field on any problem.
TcnWeightFile read_tcn_weight_file(const std::string& path);

/// Writes `file` as JSON to `path` (values with 17 significant digits, so doubles round-trip).
/// Throws tpf::Error if the file cannot be written.
void write_tcn_weight_file(const std::string& path, const TcnWeightFile& file);

}  // namespace tpf
