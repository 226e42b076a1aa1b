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

/// A 1-joint robot whose joint is continuous (no <limit>) and that names no friction file.
std::string write_spinner_robot() {
  write_temp("spinner.urdf", R"(<robot name="spinner"><link name="base"/>
  <link name="rotor"><inertial><origin xyz="0.1 0 0"/><mass value="1"/>
    <inertia ixx="1e-3" iyy="1e-3" izz="1e-3" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="spin" type="continuous"><parent link="base"/><child link="rotor"/>
    <axis xyz="0 0 1"/></joint></robot>)");
  return write_temp("spinner.robot.json", R"({"format": "tpf-robot", "version": 1,
    "urdf": "spinner.urdf", "joints": [{"name": "spin", "gear_ratio": 100,
    "rotor_inertia": 1e-6, "torque_constant": 2, "current_limit": 1000}]})");
}

TEST(Scenario, InitialPoseOutsideTheJointLimitsIsRefusedNamingJointAndLimit) {
  // Was: accepted; the twin started beyond the end stop. arm4's joint2 turns in [-2, 2] rad.
  const std::string path =
      write_temp("tpf_s_beyond.json", R"({"kind":"excitation","initial_q":[0, 2.5, 0, 0]})");
  EXPECT_EQ(error_of(path), path +
                                ": initial_q[1]: 2.5 rad is outside the limits of joint 'joint2', "
                                "[-2, 2] rad (<limit> in " TPF_DATA_DIR "/arm4.urdf)");
  const std::string below =
      write_temp("tpf_s_below.json", R"({"kind":"excitation","initial_q":[0, 0, -3.2, 0]})");
  EXPECT_NE(
      error_of(below).find(
          "initial_q[2]: -3.2 rad is outside the limits of joint 'joint3', [-3.14159, 1.5708]"),
      std::string::npos);
  // On the limit is inside.
  const Scenario at = load_scenario(
      write_temp("tpf_s_at.json", R"({"kind":"excitation","initial_q":[0, 2, 0, 0]})"));
  EXPECT_DOUBLE_EQ(at.initial_q[1], 2.0);
}

TEST(Scenario, FrictionNoneNeedsNoFrictionFileAndAContinuousJointTakesAnyAngle) {
  // Was: "friction: no friction file" even with effects.friction "none".
  const std::string robot = write_spinner_robot();
  const Scenario s = load_scenario(write_temp("tpf_s_spin.json", R"({"kind":"excitation",
    "robot":"spinner.robot.json","initial_q":[40],"effects":{"friction":"none"}})"));
  EXPECT_EQ(s.effects.friction, tpf::offline::EffectsConfig::Friction::kNone);
  EXPECT_EQ(s.friction_file, "");
  EXPECT_DOUBLE_EQ(s.initial_q[0], 40.0);
  // With friction on, the file is still required.
  const std::string on =
      write_temp("tpf_s_spin_on.json", R"({"kind":"excitation","robot":"spinner.robot.json"})");
  EXPECT_EQ(error_of(on), on +
                              ": friction: no friction file: name one here or as \"friction\" "
                              "in " +
                              robot + ", or set effects.friction to \"none\"");
  // The robot file's friction file goes unused when friction is off.
  const Scenario arm = load_scenario(
      write_temp("tpf_s_arm_none.json", R"({"kind":"excitation","effects":{"friction":"none"}})"));
  EXPECT_EQ(arm.friction_file, "");
}

}  // namespace
