// Scenario files: the shipped ones load; unknown keys and impossible values are refused with a
// message naming the file and the key path.
#include "offline/sim/scenario.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "support/temp_dir.hpp"
#include "tpf/common/error.hpp"

namespace {

using tpf::offline::load_scenario;
using tpf::offline::Scenario;

/// This test program's files, removed at its end.
const tpf::test::TempDir kFiles("scenario_test");

std::string write_temp(const std::string& name, const std::string& text) {
  const auto path = kFiles / name;
  std::ofstream(path) << text;
  return path.string();
}

std::string error_of(const std::string& path) {
  try {
    load_scenario(path);
  } catch (const tpf::Error& e) {
    return e.what();
  }
  return "";
}

TEST(Scenario, ShippedScenariosLoad) {
  const std::string dir = TPF_TEST_DATA_DIR "/scenarios/";
  const Scenario e = load_scenario(dir + "excitation.json");
  EXPECT_EQ(e.kind, Scenario::Kind::kExcitation);
  EXPECT_DOUBLE_EQ(e.duration_s, 600.0);
  EXPECT_EQ(e.effects.friction, tpf::offline::EffectsConfig::Friction::kLuGre);
  EXPECT_TRUE(std::filesystem::exists(e.friction_file));
  const Scenario u = load_scenario(dir + "excitation-undeclared.json");
  EXPECT_TRUE(u.effects.ripple.enabled);
  EXPECT_DOUBLE_EQ(u.effects.ripple.amplitude[1], 0.35);
  EXPECT_DOUBLE_EQ(u.effects.payload.mass, 0.6);
  EXPECT_TRUE(u.effects.thermal.enabled);
  EXPECT_EQ(load_scenario(dir + "static-contacts.json").kind, Scenario::Kind::kStaticContacts);
  EXPECT_EQ(load_scenario(dir + "teaching.json").kind, Scenario::Kind::kTeaching);
}

TEST(Scenario, UnknownKeyIsRefusedWithFileAndKeyPath) {
  const std::string path = write_temp(
      "tpf_scenario_unknown.json",
      R"({"kind":"excitation","effects":{"ripple":{"enabled":true,"amplitude":[1,1,1,1]}}})");
  const std::string msg = error_of(path);
  EXPECT_NE(msg.find(path), std::string::npos) << msg;
  EXPECT_NE(msg.find("effects.ripple.amplitude: unknown key"), std::string::npos) << msg;

  const std::string top = error_of(
      write_temp("tpf_scenario_unknown_top.json", R"({"kind":"excitation","durration_s":5})"));
  EXPECT_NE(top.find("durration_s: unknown key"), std::string::npos) << top;
}

TEST(Scenario, ImpossibleValuesAreRefusedByKey) {
  const auto check = [](const std::string& name, const std::string& json,
                        const std::string& expected) {
    const std::string msg = error_of(write_temp(name, json));
    EXPECT_NE(msg.find(expected), std::string::npos) << msg;
  };
  check("tpf_s1.json", R"({"kind":"excitation","duration_s":-3})", "duration_s: must be in");
  check("tpf_s2.json", R"({"kind":"shaking"})", "kind: must be one of");
  check("tpf_s3.json", R"({"kind":"excitation","sensors":{"drop_probability":2}})",
        "sensors.drop_probability: must be in");
  check("tpf_s4.json", R"({"kind":"excitation","excitation":{"speed_min":0.5,"speed_max":0.1}})",
        "excitation.speed_max: must not be smaller than speed_min");
  check("tpf_s5.json", R"({"kind":"excitation","effects":{"friction":"magic"}})",
        "effects.friction: must be one of lugre, stribeck, none");
  check("tpf_s6.json", R"({"kind":"excitation","initial_q":[0,0,0]})",
        "initial_q: must be an array of 4 numbers");
  check("tpf_s7.json", R"({"kind":"excitation","inner_rate_hz":1000,"log_rate_hz":300})",
        "log_rate_hz: inner_rate_hz must be an integer multiple");
  check("tpf_s8.json", R"({"kind":"excitation","friction":"no_such_file.json"})",
        "friction: file not found");
  check("tpf_s9.json", R"({"kind":"excitation","effects":{"payload":{"mass_kg":"heavy"}}})",
        "effects.payload.mass_kg: must be a number");
  check("tpf_s10.json", R"({"kind":"excitation",)", "tpf_s10.json:1: not valid JSON");
}

}  // namespace
