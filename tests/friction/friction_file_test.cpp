// Friction parameter files: the twin's file loads; bad files are refused naming file and field.
#include "tpf/friction/friction_file.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "support/temp_dir.hpp"
#include "tpf/common/error.hpp"

namespace {

/// This test program's files, removed at its end.
const tpf::test::TempDir kFiles("friction_test");

std::string write_temp(const std::string& name, const std::string& text) {
  const auto path = kFiles / name;
  std::ofstream(path) << text;
  return path.string();
}

std::string error_of(const std::string& path) {
  try {
    tpf::load_lugre_parameters<double, 2>(path);
  } catch (const tpf::Error& e) {
    return e.what();
  }
  return "";
}

const char* kValid = R"({"coulomb":[1,2],"static":[1.5,2.5],"stribeck_velocity":[0.1,0.1],
  "stribeck_exponent":[2,2],"viscous":[0.5,0.6],"bristle_stiffness":[1e4,1e4],
  "bristle_damping":[10,10]})";

TEST(FrictionFile, LoadsTheTwinParameters) {
  const auto p = tpf::load_lugre_parameters<double, 4>(TPF_TEST_DATA_DIR "/arm4.friction.json");
  EXPECT_DOUBLE_EQ(p.stribeck.coulomb[0], 1.05);
  EXPECT_DOUBLE_EQ(p.stribeck.load_viscous[3], 0.100);
  EXPECT_DOUBLE_EQ(p.bristle_stiffness[1], 1.4e4);
  EXPECT_DOUBLE_EQ(p.bristle_damping[0], 100.0);
  EXPECT_EQ(tpf::friction_effort_unit(TPF_TEST_DATA_DIR "/arm4.friction.json"), "N*m");
  const auto s = tpf::load_stribeck_parameters<double, 4>(TPF_TEST_DATA_DIR "/arm4.friction.json");
  EXPECT_DOUBLE_EQ(s.static_friction[2], 0.90);
}

TEST(FrictionFile, ValidSmallFileLoadsWithDefaultsForOptionalKeys) {
  const auto p = tpf::load_lugre_parameters<double, 2>(write_temp("tpf_fric_ok.json", kValid));
  EXPECT_DOUBLE_EQ(p.stribeck.static_friction[1], 2.5);
  EXPECT_EQ(p.stribeck.load_coulomb[1], 0.0);
}

TEST(FrictionFile, UnknownKeyIsRefusedByName) {
  std::string text = kValid;
  text.insert(1, "\"viscuos\":[1,1],");
  const std::string path = write_temp("tpf_fric_unknown.json", text);
  const std::string msg = error_of(path);
  EXPECT_NE(msg.find(path), std::string::npos) << msg;
  EXPECT_NE(msg.find("viscuos"), std::string::npos) << msg;
}

TEST(FrictionFile, ImpossibleValuesAreRefusedByField) {
  std::string text = kValid;
  text.replace(text.find("0.1,0.1"), 7, "0.1,-0.1");
  const std::string msg = error_of(write_temp("tpf_fric_negative.json", text));
  EXPECT_NE(msg.find("stribeck_velocity[1]"), std::string::npos) << msg;
  EXPECT_NE(msg.find("positive"), std::string::npos) << msg;

  std::string wrong_size = kValid;
  wrong_size.replace(wrong_size.find("[1,2]"), 5, "[1,2,3]");
  EXPECT_NE(error_of(write_temp("tpf_fric_size.json", wrong_size)).find("coulomb"),
            std::string::npos);
}

TEST(FrictionFile, MissingKeyAndMissingFileAreReported) {
  std::string text = kValid;
  text.replace(text.find("\"bristle_damping\":[10,10]"), 25, "\"description\":\"x\"");
  EXPECT_NE(error_of(write_temp("tpf_fric_missing.json", text)).find("bristle_damping: missing"),
            std::string::npos);
  EXPECT_NE(error_of("/nonexistent/friction.json").find("cannot open"), std::string::npos);
}

}  // namespace

TEST(FrictionFile, RunTimeCountIsTheArraysLength) {
  const std::string path = TPF_TEST_DATA_DIR "/arm4.friction.json";
  const auto any = tpf::load_lugre_parameters(path);
  const auto four = tpf::load_lugre_parameters<double, 4>(path);
  ASSERT_EQ(any.stribeck.coulomb.size(), 4);
  EXPECT_EQ(any.stribeck.coulomb, four.stribeck.coulomb);
  EXPECT_EQ(any.stribeck.load_viscous, four.stribeck.load_viscous);
  EXPECT_EQ(any.bristle_stiffness, four.bristle_stiffness);
  // Keys the file does not hold keep the defaults, sized for the file's joints.
  EXPECT_EQ(any.stribeck.neighbour_load_coulomb.rows(), 4);
  EXPECT_EQ(any.stribeck.coulomb_asymmetry, Eigen::VectorXd::Zero(4));

  std::string nine = R"({"coulomb":[1,1,1,1,1,1,1,1,3],"static":[2,2,2,2,2,2,2,2,2],
    "stribeck_velocity":[1,1,1,1,1,1,1,1,1],"stribeck_exponent":[2,2,2,2,2,2,2,2,2],
    "viscous":[0,0,0,0,0,0,0,0,0.5]})";
  const auto p = tpf::load_stribeck_parameters(write_temp("tpf_fric_nine.json", nine));
  ASSERT_EQ(p.coulomb.size(), 9);
  EXPECT_EQ(p.coulomb[8], 3.0);
  EXPECT_EQ(p.viscous[8], 0.5);
}

TEST(FrictionFile, ArraysOfAnotherLengthAreRefusedByField) {
  // The arrays disagree: the count comes from "coulomb" (2), "viscous" holds 3.
  std::string text = kValid;
  text.replace(text.find("\"viscous\":[0.5,0.6]"), 19, "\"viscous\":[0.5,0.6,0.7]");
  const std::string path = write_temp("tpf_fric_length.json", text);
  try {
    tpf::load_lugre_parameters(path);
    ADD_FAILURE() << "a 3-number viscous array of a 2-joint file was accepted";
  } catch (const tpf::Error& e) {
    EXPECT_NE(std::string(e.what()).find("viscous"), std::string::npos) << e.what();
  }
  // A 2-joint file asked for as a 4-joint program's file.
  try {
    tpf::load_lugre_parameters<double, 4>(write_temp("tpf_fric_two.json", kValid));
    ADD_FAILURE() << "a 2-joint file was accepted as a 4-joint one";
  } catch (const tpf::Error& e) {
    EXPECT_NE(std::string(e.what()).find("coulomb"), std::string::npos) << e.what();
  }
}
