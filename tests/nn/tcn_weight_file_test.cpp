// Weight file: round trip, refusal of mismatched architecture and tensor shapes, bad fields.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "tcn_test_support.hpp"
#include "tpf/common/error.hpp"
#include "tpf/nn/load_tcn_weights.hpp"

namespace tpf {
namespace {

std::string temp_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() /
          ("tpf_nn_" + std::to_string(::getpid()) + "_" + name + ".json"))
      .string();
}

std::string load_error(const std::string& path) {
  Tcn<double, 4, 8, 3, 4, 1> tcn;
  try {
    load_tcn_weights(path, tcn);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

nlohmann::json written_json(const std::string& path) {
  write_tcn_weight_file(path,
                        offline::to_weight_file(test::random_tcn_parameters({4, 8, 3, 4, 1}, 5)));
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

void write_json(const std::string& path, const nlohmann::json& json) {
  std::ofstream(path) << json.dump();
}

TEST(TcnWeightFile, RoundTripIsExact) {
  const std::string path = temp_path("round_trip");
  offline::TcnParameters p = test::random_tcn_parameters({4, 8, 3, 4, 2}, 3);
  write_tcn_weight_file(path, offline::to_weight_file(p));
  offline::TcnParameters back = offline::from_weight_file(read_tcn_weight_file(path));
  EXPECT_EQ(offline::flatten(p), offline::flatten(back));
  EXPECT_EQ(p.input_mean, back.input_mean);
  EXPECT_EQ(p.input_std, back.input_std);
  std::filesystem::remove(path);
}

TEST(TcnWeightFile, LoadFoldsNormalisationAndPrewarmsAtTheMean) {
  const std::string path = temp_path("load");
  const offline::TcnParameters p = test::random_tcn_parameters({4, 8, 3, 4, 1}, 4);
  write_tcn_weight_file(path, offline::to_weight_file(p));
  Tcn<double, 4, 8, 3, 4, 1> tcn;
  load_tcn_weights(path, tcn);
  Eigen::MatrixXd steady(4, p.architecture.receptive_field());
  steady.colwise() = p.input_mean;
  const Eigen::MatrixXd naive = test::naive_tcn(p, steady);
  EXPECT_NEAR(tcn.low()(0), naive(0, 0), 1e-12);
  EXPECT_NEAR(tcn.high()(0), naive(1, 0), 1e-12);
  std::filesystem::remove(path);
}

TEST(TcnWeightFile, TensorShapeMismatchNamesFileTensorAndBothShapes) {
  const std::string path = temp_path("shape");
  nlohmann::json json = written_json(path);
  json["tensors"]["blocks.1.conv.weight"]["shape"] = {16, 4, 4};  // same count, wrong shape
  write_json(path, json);
  const std::string message = load_error(path);
  EXPECT_NE(message.find(path), std::string::npos) << message;
  EXPECT_NE(message.find("tensors.blocks.1.conv.weight"), std::string::npos) << message;
  EXPECT_NE(message.find("[16, 4, 4]"), std::string::npos) << message;
  EXPECT_NE(message.find("[8, 8, 4]"), std::string::npos) << message;
  std::filesystem::remove(path);
}

TEST(TcnWeightFile, ArchitectureMismatchIsRefusedAndLeavesTheEngineUntouched) {
  const std::string path = temp_path("arch");
  write_tcn_weight_file(path,
                        offline::to_weight_file(test::random_tcn_parameters({4, 8, 3, 4, 1}, 6)));
  Tcn<double, 4, 16, 3, 4, 1> tcn;
  try {
    load_tcn_weights(path, tcn);
    FAIL() << "a 16-channel engine accepted an 8-channel file";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("architecture.hidden: 8 in the file, 16 expected"), std::string::npos)
        << message;
  }
  EXPECT_EQ(tcn.weights().input_bias.norm(), 0.0);
  std::filesystem::remove(path);
}

TEST(TcnWeightFile, MissingTensorAndBadValuesAreNamed) {
  const std::string path = temp_path("bad");
  nlohmann::json json = written_json(path);
  nlohmann::json missing = json;
  missing["tensors"].erase("head_high.bias");
  write_json(path, missing);
  EXPECT_NE(load_error(path).find("tensors.head_high.bias: missing"), std::string::npos);

  nlohmann::json extra = json;
  extra["tensors"]["blocks.3.conv.bias"] = json["tensors"]["blocks.2.conv.bias"];
  write_json(path, extra);
  EXPECT_NE(load_error(path).find("tensors.blocks.3.conv.bias: not a tensor of the compiled"),
            std::string::npos);

  nlohmann::json nan = json;
  nan["tensors"]["blocks.0.conv.bias"]["values"][3] = nullptr;  // what a NaN becomes in JSON
  write_json(path, nan);
  EXPECT_NE(load_error(path).find("tensors.blocks.0.conv.bias.values: element 3"),
            std::string::npos);

  nlohmann::json count = json;
  count["tensors"]["head_low.weight"]["values"].erase(0);
  write_json(path, count);
  EXPECT_NE(load_error(path).find("7 values for shape [1, 8]"), std::string::npos);

  nlohmann::json version = json;
  version["version"] = 3;
  write_json(path, version);
  EXPECT_NE(load_error(path).find("version: unsupported version 3"), std::string::npos);
  version["version"] = 1;  // torques in the training log's unit: refused, naming the converter
  write_json(path, version);
  EXPECT_NE(load_error(path).find("version: is 1"), std::string::npos);
  EXPECT_NE(load_error(path).find("tpf upgrade"), std::string::npos);

  nlohmann::json std_zero = json;
  std_zero["normalisation"]["std"][1] = 0.0;
  write_json(path, std_zero);
  EXPECT_NE(load_error(path).find("normalisation.std: element 1 must be > 0"), std::string::npos);

  std::ofstream(path) << "{ not json";
  EXPECT_NE(load_error(path).find("not valid JSON"), std::string::npos);
  std::filesystem::remove(path);
  EXPECT_NE(load_error(path).find("cannot open"), std::string::npos);
}

}  // namespace
}  // namespace tpf
