// Reading, validating and writing TCN weight files (start-up code: allocates and throws).
#include "tpf/nn/tcn_weight_file.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <nlohmann/json.hpp>
#include <numeric>
#include <sstream>

#include "core/common/atomic_file.hpp"
#include "core/common/json_object.hpp"
#include "core/common/json_parse.hpp"
#include "core/common/unoptimised_when_sanitized.hpp"
#include "tpf/common/error.hpp"

TPF_UNOPTIMISED_WHEN_SANITIZED_BEGIN

namespace tpf {
namespace {

constexpr std::string_view kTcnFormat = "tpf-tcn-weights";

std::string shape_text(const std::vector<int>& shape) {
  std::string text = "[";
  for (std::size_t i = 0; i < shape.size(); ++i) {
    if (i > 0) text += ", ";
    text += std::to_string(shape[i]);
  }
  return text + "]";
}

[[noreturn]] void fail(const std::string& path, std::string_view field, std::string_view what) {
  throw Error::at(path, 0, field, what);
}

const nlohmann::json& member(const nlohmann::json& object, const std::string& key,
                             const std::string& path, const std::string& field) {
  if (!object.is_object() || !object.contains(key)) fail(path, field, "missing");
  return object.at(key);
}

int positive_int(const nlohmann::json& object, const std::string& key, const std::string& path,
                 const std::string& prefix) {
  const std::string field = prefix + "." + key;
  const nlohmann::json& value = member(object, key, path, field);
  if (!value.is_number_integer() || value.get<long long>() <= 0 ||
      value.get<long long>() > 1'000'000) {
    fail(path, field, "must be a positive integer, got " + value.dump());
  }
  return value.get<int>();
}

std::vector<double> finite_numbers(const nlohmann::json& array, const std::string& path,
                                   const std::string& field) {
  if (!array.is_array()) fail(path, field, "must be an array of numbers");
  std::vector<double> values;
  values.reserve(array.size());
  for (std::size_t i = 0; i < array.size(); ++i) {
    if (!array[i].is_number()) {
      fail(path, field, "element " + std::to_string(i) + " is not a number: " + array[i].dump());
    }
    const double v = array[i].get<double>();
    if (!std::isfinite(v)) fail(path, field, "element " + std::to_string(i) + " is not finite");
    values.push_back(v);
  }
  return values;
}

TcnTensor read_tensor(const nlohmann::json& json, const std::string& path,
                      const std::string& field) {
  TcnTensor tensor;
  const nlohmann::json& shape = member(json, "shape", path, field + ".shape");
  if (!shape.is_array() || shape.empty()) fail(path, field + ".shape", "must be a non-empty array");
  for (const auto& d : shape) {
    if (!d.is_number_integer() || d.get<long long>() <= 0 || d.get<long long>() > 1'000'000) {
      fail(path, field + ".shape", "dimensions must be positive integers, got " + shape.dump());
    }
    tensor.shape.push_back(d.get<int>());
  }
  tensor.values =
      finite_numbers(member(json, "values", path, field + ".values"), path, field + ".values");
  // Dimensions are ≤ 10⁶ < 2²⁰: capping the running product at 2⁴⁰ keeps it exact up to any real
  // value count and free of signed overflow for any number of dimensions.
  long long expected = 1;
  for (const int d : tensor.shape)
    expected = std::min(expected * d, 1LL << 40);
  if (static_cast<long long>(tensor.values.size()) != expected) {
    fail(path, field + ".values",
         std::to_string(tensor.values.size()) + " values for shape " + shape_text(tensor.shape) +
             " (" + std::to_string(expected) + " expected)");
  }
  return tensor;
}

}  // namespace

std::string tcn_conv_weight_name(int block) {
  return "blocks." + std::to_string(block) + ".conv.weight";
}
std::string tcn_conv_bias_name(int block) {
  return "blocks." + std::to_string(block) + ".conv.bias";
}
std::string tcn_downsample_name() {
  return "blocks.0.downsample.weight";
}
std::string tcn_head_weight_name(bool high) {
  return high ? "head_high.weight" : "head_low.weight";
}
std::string tcn_head_bias_name(bool high) {
  return high ? "head_high.bias" : "head_low.bias";
}

const TcnTensor& TcnWeightFile::tensor(std::string_view name, const std::vector<int>& shape) const {
  const std::string field = "tensors." + std::string(name);
  const auto it = tensors.find(std::string(name));
  if (it == tensors.end()) fail(path, field, "missing (expected shape " + shape_text(shape) + ")");
  if (it->second.shape != shape) {
    fail(path, field,
         "shape " + shape_text(it->second.shape) + " in the file, " + shape_text(shape) +
             " expected by the compiled network");
  }
  return it->second;
}

void TcnWeightFile::refuse_unexpected_tensors(const std::vector<std::string>& expected) const {
  for (const auto& [name, tensor] : tensors) {
    if (std::find(expected.begin(), expected.end(), name) == expected.end()) {
      fail(path, "tensors." + name, "not a tensor of the compiled network");
    }
  }
}

void TcnWeightFile::require_architecture(int in, int hid, int lev, int ker, int out) const {
  const std::pair<const char*, std::pair<int, int>> checks[] = {{"inputs", {inputs, in}},
                                                                {"hidden", {hidden, hid}},
                                                                {"levels", {levels, lev}},
                                                                {"kernel", {kernel, ker}},
                                                                {"outputs", {outputs, out}}};
  for (const auto& [name, values] : checks) {
    if (values.first != values.second) {
      fail(path, std::string("architecture.") + name,
           std::to_string(values.first) + " in the file, " + std::to_string(values.second) +
               " expected by the compiled network");
    }
  }
}

namespace {

// "held_out": one array of `outputs` gains (numbers ≤ 1, or null: not scored) per regime.
void read_held_out(const nlohmann::json& held_out, const std::string& path, TcnWeightFile& file) {
  if (!held_out.is_object())
    fail(path, "held_out", "must be an object of gains per regime, got " + held_out.dump());
  for (std::size_t r = 0; r < TcnWeightFile::kHeldOutRegimes.size(); ++r) {
    const std::string field = std::string("held_out.") + TcnWeightFile::kHeldOutRegimes[r];
    const nlohmann::json& gains = member(held_out, TcnWeightFile::kHeldOutRegimes[r], path, field);
    if (!gains.is_array() || static_cast<int>(gains.size()) != file.outputs)
      fail(path, field,
           "must be an array of " + std::to_string(file.outputs) +
               " gains (architecture.outputs), got " + gains.dump());
    for (std::size_t o = 0; o < gains.size(); ++o) {
      if (gains[o].is_null()) {
        file.held_out_gain[r].push_back(std::numeric_limits<double>::quiet_NaN());
        continue;
      }
      if (!gains[o].is_number() || !(gains[o].get<double>() <= 1.0))
        fail(path, field,
             "element " + std::to_string(o) +
                 " must be a gain ≤ 1 (1 − RMSE with / without the network) or null, got " +
                 gains[o].dump());
      file.held_out_gain[r].push_back(gains[o].get<double>());
    }
  }
  for (const auto& [key, value] : held_out.items()) {
    if (std::find(TcnWeightFile::kHeldOutRegimes.begin(), TcnWeightFile::kHeldOutRegimes.end(),
                  key) == TcnWeightFile::kHeldOutRegimes.end())
      fail(path, "held_out." + key,
           "not a regime (static, static-to-kinetic, moving); value " + value.dump());
  }
}

}  // namespace

TcnWeightFile read_tcn_weight_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) fail(path, "", "cannot open the TCN weight file");
  const nlohmann::json json = tpf::json::parse_file(path);

  const nlohmann::json& format = member(json, "format", path, "format");
  if (format != kTcnFormat)
    fail(path, "format", "expected \"tpf-tcn-weights\", got " + format.dump());
  const nlohmann::json& version = member(json, "version", path, "version");
  if (version == 1)
    fail(path, "version",
         "is 1: a compensator's torque inputs (τ̂_fric,s, τ_fric,nom) and outputs in the training "
         "log's effort unit (mA for a log of currents); this tpf reads version 2, in N*m. Convert "
         "the files with `tpf upgrade --weights PATH --params PARAMS` (PARAMS: the "
         "version-1 parameter file it was trained with), or train again");
  if (version != TcnWeightFile::kVersion) {
    fail(path, "version", "unsupported version " + version.dump() + " (this build reads 2)");
  }

  TcnWeightFile file;
  file.path = path;
  const nlohmann::json& arch = member(json, "architecture", path, "architecture");
  file.inputs = positive_int(arch, "inputs", path, "architecture");
  file.hidden = positive_int(arch, "hidden", path, "architecture");
  file.levels = positive_int(arch, "levels", path, "architecture");
  file.kernel = positive_int(arch, "kernel", path, "architecture");
  file.outputs = positive_int(arch, "outputs", path, "architecture");
  if (file.levels > 16) fail(path, "architecture.levels", "at most 16 levels are supported");
  const nlohmann::json& activation = member(arch, "activation", path, "architecture.activation");
  if (activation != "relu") {
    fail(path, "architecture.activation", "only \"relu\" is supported, got " + activation.dump());
  }

  const nlohmann::json& norm = member(json, "normalisation", path, "normalisation");
  file.input_mean =
      finite_numbers(member(norm, "mean", path, "normalisation.mean"), path, "normalisation.mean");
  file.input_std =
      finite_numbers(member(norm, "std", path, "normalisation.std"), path, "normalisation.std");
  for (const auto* field : {"mean", "std"}) {
    const auto& v = std::string(field) == "mean" ? file.input_mean : file.input_std;
    if (static_cast<int>(v.size()) != file.inputs) {
      fail(path, std::string("normalisation.") + field,
           std::to_string(v.size()) + " values, architecture.inputs is " +
               std::to_string(file.inputs));
    }
  }
  for (std::size_t i = 0; i < file.input_std.size(); ++i) {
    if (!(file.input_std[i] > 0.0)) {
      fail(path, "normalisation.std", "element " + std::to_string(i) + " must be > 0");
    }
  }

  const nlohmann::json& tensors = member(json, "tensors", path, "tensors");
  if (!tensors.is_object()) fail(path, "tensors", "must be an object of named tensors");
  for (const auto& [name, value] : tensors.items()) {
    file.tensors.emplace(name, read_tensor(value, path, "tensors." + name));
  }
  if (json.contains("held_out")) read_held_out(json["held_out"], path, file);
  return file;
}

void write_tcn_weight_file(const std::string& path, const TcnWeightFile& file) {
  nlohmann::json json;
  json["format"] = kTcnFormat;
  json["version"] = TcnWeightFile::kVersion;
  std::vector<int> dilations;
  for (int l = 0; l < file.levels; ++l)
    dilations.push_back(1 << l);
  json["architecture"] = {{"inputs", file.inputs},
                          {"hidden", file.hidden},
                          {"levels", file.levels},
                          {"kernel", file.kernel},
                          {"outputs", file.outputs},
                          {"activation", "relu"},
                          {"dilations", dilations},
                          {"receptive_field", 1 + (file.kernel - 1) * ((1 << file.levels) - 1)}};
  json["normalisation"] = {{"mean", file.input_mean}, {"std", file.input_std}};
  nlohmann::json tensors = nlohmann::json::object();
  for (const auto& [name, tensor] : file.tensors) {
    tensors[name] = {{"shape", tensor.shape}, {"values", tensor.values}};
  }
  json["tensors"] = std::move(tensors);
  if (!file.held_out_gain[0].empty()) {
    nlohmann::json held_out = nlohmann::json::object();
    for (std::size_t r = 0; r < TcnWeightFile::kHeldOutRegimes.size(); ++r) {
      nlohmann::json gains = nlohmann::json::array();
      for (double g : file.held_out_gain[r])
        gains.push_back(std::isfinite(g) ? nlohmann::json(g) : nlohmann::json(nullptr));
      held_out[TcnWeightFile::kHeldOutRegimes[r]] = std::move(gains);
    }
    json["held_out"] = std::move(held_out);
  }
  json::require_finite(json, path);
  write_file_atomically(path, json.dump(1) + "\n");
}

}  // namespace tpf

TPF_UNOPTIMISED_WHEN_SANITIZED_END
