// JSON files (robot, pads, friction, scenario, weights) that escaped the tpf::Error contract:
// each is a fixed regression test here.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/common/json_object.hpp"
#include "core/common/json_parse.hpp"
#include "support/temp_dir.hpp"
#include "tpf/common/error.hpp"
#include "tpf/friction/friction_file.hpp"
#include "tpf/nn/tcn_weight_file.hpp"

namespace tpf {
namespace {

std::filesystem::path write(const test::TempDir& dir, const std::string& name,
                            const std::string& text) {
  const auto path = dir / name;
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

template <typename F>
std::string message_of(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  } catch (const std::exception& e) {
    return std::string("not a tpf::Error: ") + e.what();
  }
  return "(no error)";
}

// A number beyond the double range (1e999) makes nlohmann::json throw out_of_range (406), not
// parse_error: it escaped every loader as "tpf: unexpected error: [json.exception.out_of_range.406]
// number overflow parsing '1e999'", exit 2, no file name. Now it names the file and the line.
TEST(JsonFuzzRegressions, NumberBeyondTheDoubleRangeNamesFileAndLine) {
  const test::TempDir dir("json_regression");
  const auto path = write(dir, "overflow.json",
                          "{\n  \"format\": \"tpf-friction\",\n  \"coulomb\": "
                          "[1, 1e999, 1, 1]\n}\n");
  const std::string file = path.string();
  for (const std::string& msg : {message_of([&] { json::parse_file(path); }),
                                 message_of([&] { json::Object::read_file(path); }),
                                 message_of([&] { load_stribeck_parameters<double, 4>(file); }),
                                 message_of([&] { read_tcn_weight_file(file); })}) {
    EXPECT_EQ(msg.rfind(file + ":3: not valid JSON: ", 0), 0u) << msg;
    EXPECT_NE(msg.find("1e999"), std::string::npos) << msg;
  }
}

// 300 000 nested '[': parsing succeeded, then copying the value (Object) recursed once per level
// and overflowed the stack (ASan stack-overflow). Nesting is now refused past 64 levels, naming
// the line where it happens, in every loader.
TEST(JsonFuzzRegressions, DeepNestingIsRefusedNamingTheLine) {
  const test::TempDir dir("json_regression");
  const auto path =
      write(dir, "deep.json",
            "{\"format\":\n" + std::string(300000, '[') + std::string(300000, ']') + "}");
  const std::string file = path.string();
  for (const std::string& msg : {message_of([&] { json::parse_file(path); }),
                                 message_of([&] { json::Object::read_file(path); }),
                                 message_of([&] { read_tcn_weight_file(file); })})
    EXPECT_EQ(msg, file + ":2: nested deeper than 64 levels");
}

// A tensor shape of four 10⁶ dimensions overflowed the signed product of the shape (UBSan
// signed-integer-overflow); it is a value-count mismatch like any other.
TEST(JsonFuzzRegressions, HugeTensorShapeIsAValueCountMismatch) {
  const std::string msg = message_of([] {
    read_tcn_weight_file(std::string(TPF_RELIABILITY_CORPUS_DIR) +
                         "/fuzz_tcn_weights/crash-shape-product-overflow.json");
  });
  EXPECT_NE(msg.find("tensors.blocks.0.conv.weight.values"), std::string::npos) << msg;
}

}  // namespace
}  // namespace tpf
