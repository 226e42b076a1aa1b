// JSON files (robot, pads, friction, scenario, weights) that escaped the tpf::Error contract:
// each is a fixed regression test here.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "tpf/common/error.hpp"
#include "tpf/common/json_object.hpp"
#include "tpf/friction/friction_file.hpp"
#include "tpf/nn/tcn_weight_file.hpp"

namespace tpf {
namespace {

std::filesystem::path write(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / ("tpf_json_regression_" + name);
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
  const auto path = write("overflow.json",
                          "{\n  \"format\": \"tpf-friction\",\n  \"coulomb\": "
                          "[1, 1e999, 1, 1]\n}\n");
  const std::string file = path.string();
  for (const std::string& msg : {message_of([&] { json::Object::read_file(path); }),
                                 message_of([&] { load_stribeck_parameters<double, 4>(file); }),
                                 message_of([&] { read_tcn_weight_file(file); })}) {
    EXPECT_EQ(msg.rfind(file + ":3: not valid JSON: ", 0), 0u) << msg;
    EXPECT_NE(msg.find("1e999"), std::string::npos) << msg;
  }
  std::filesystem::remove(path);
}

// A huge "version" was cast to int for the message (undefined behaviour, UBSan
// float-cast-overflow). It is now refused by range, quoted as written.
TEST(JsonFuzzRegressions, HugeVersionIsQuotedNotCast) {
  const auto path = write("version.json", R"({"format": "tpf-pads", "version": 1e300})");
  const std::string msg = message_of([&] { json::Object::read_document(path, "tpf-pads", 1); });
  EXPECT_NE(msg.find("version: must be in"), std::string::npos) << msg;
  EXPECT_NE(msg.find("got 1e+300"), std::string::npos) << msg;
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace tpf
