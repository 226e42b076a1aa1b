// The estimator parameter file: every field survives save → load exactly, and a file with a
// missing, unknown or bad field is refused naming the file and the field. The field counts below
// guard the round trip: a field added to EstimatorParameters (or a nested settings struct) fails
// to compile here until it is saved, loaded, set and compared.
#include "tpf/estimation/estimator_parameter_file.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tpf/common/error.hpp"

namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;
using Parameters = tpf::EstimatorParameters<double, 4>;

/// Converts to any member type (unevaluated only): T{AnyField{}, …} compiles for at most as many
/// initialisers as T has members.
struct AnyField {
  template <typename T>
  operator T() const;
};

/// The number of members of aggregate T.
template <typename T, typename... Fields>
constexpr int field_count() {
  if constexpr (requires { T{Fields{}..., AnyField{}}; })
    return field_count<T, Fields..., AnyField>();
  else
    return static_cast<int>(sizeof...(Fields));
}

// If one of these fails, a field was added: serialise it in estimator_parameter_file.cpp, then
// set it in every_field_changed() and compare it in expect_same() below.
static_assert(field_count<Parameters>() == 18, "EstimatorParameters changed");
static_assert(field_count<tpf::StaticFrictionSettings<double>>() == 4, "StaticFriction changed");
static_assert(field_count<tpf::SkinSettings<double>>() == 3, "SkinSettings changed");
static_assert(field_count<tpf::PadDetectorSettings<double>>() == 4, "PadDetector changed");
static_assert(field_count<tpf::ContactForceSettings<double>>() == 6, "ContactForce changed");

/// Every field different from its default (and from every other field).
Parameters every_field_changed() {
  Parameters p;
  p.sample_period_s = 0.001;
  p.max_gap_factor = 2.25;
  p.position_margin_rad = 0.07;
  p.acceleration_cutoff_hz = 33.0;
  p.acceleration_damping = 0.71;
  p.frozen_limit_samples = 123;
  p.stuck_pad_limit_samples = 45;
  p.static_friction.static_velocity = 2.2e-3;
  p.static_friction.baseline_lead_s = 0.006;
  p.static_friction.baseline_window_s = 0.0175;
  p.static_friction.stop_policy = tpf::StopPolicy::KeepStale;
  p.skin.detector.cutoff_hz = 41.5;
  p.skin.detector.on_level_kpa = 0.0823;
  p.skin.detector.off_level_kpa = 0.0411;
  p.skin.detector.offset_time_constant_s = 3.5;
  p.skin.force_gain = 0.2666666666666667;
  p.skin.full_scale_kpa = 40.1;
  p.wrench.torque_noise_nm = 0.061;
  p.wrench.prior_relative = 0.45;
  p.wrench.prior_floor_n = 1.3;
  p.wrench.shear_relative = 0.55;
  p.wrench.min_inverse_condition = 0.031;
  p.wrench.shear_regularisation = 2e-12;
  p.nominal_sigma << 11.1, 12.2, 13.3, 1.0 / 3.0;
  p.fused_sigma << 5.5, 6.6, 7.7, 0.1 + 0.2;
  p.dead_band_factor = 1.75;
  p.torque_alarm_samples = 17;
  p.static_dead_band << 19.7, 20.1, 21.9, 22.3;
  p.compensator_speed_limit << 0.78, 0.77, 0.68, 0.79;
  p.compensator_acceleration_limit << 1.21, 2.13, 9.15, 3.18;
  p.compensator_min_held_out_gain = 0.07;
  return p;
}

void expect_same(const Parameters& a, const Parameters& b) {
  EXPECT_EQ(a.sample_period_s, b.sample_period_s);
  EXPECT_EQ(a.max_gap_factor, b.max_gap_factor);
  EXPECT_EQ(a.position_margin_rad, b.position_margin_rad);
  EXPECT_EQ(a.acceleration_cutoff_hz, b.acceleration_cutoff_hz);
  EXPECT_EQ(a.acceleration_damping, b.acceleration_damping);
  EXPECT_EQ(a.frozen_limit_samples, b.frozen_limit_samples);
  EXPECT_EQ(a.stuck_pad_limit_samples, b.stuck_pad_limit_samples);
  EXPECT_EQ(a.static_friction.static_velocity, b.static_friction.static_velocity);
  EXPECT_EQ(a.static_friction.baseline_lead_s, b.static_friction.baseline_lead_s);
  EXPECT_EQ(a.static_friction.baseline_window_s, b.static_friction.baseline_window_s);
  EXPECT_EQ(a.static_friction.stop_policy, b.static_friction.stop_policy);
  EXPECT_EQ(a.skin.detector.cutoff_hz, b.skin.detector.cutoff_hz);
  EXPECT_EQ(a.skin.detector.on_level_kpa, b.skin.detector.on_level_kpa);
  EXPECT_EQ(a.skin.detector.off_level_kpa, b.skin.detector.off_level_kpa);
  EXPECT_EQ(a.skin.detector.offset_time_constant_s, b.skin.detector.offset_time_constant_s);
  EXPECT_EQ(a.skin.force_gain, b.skin.force_gain);
  EXPECT_EQ(a.skin.full_scale_kpa, b.skin.full_scale_kpa);
  EXPECT_EQ(a.wrench.torque_noise_nm, b.wrench.torque_noise_nm);
  EXPECT_EQ(a.wrench.prior_relative, b.wrench.prior_relative);
  EXPECT_EQ(a.wrench.prior_floor_n, b.wrench.prior_floor_n);
  EXPECT_EQ(a.wrench.shear_relative, b.wrench.shear_relative);
  EXPECT_EQ(a.wrench.min_inverse_condition, b.wrench.min_inverse_condition);
  EXPECT_EQ(a.wrench.shear_regularisation, b.wrench.shear_regularisation);
  EXPECT_EQ(a.nominal_sigma, b.nominal_sigma);
  EXPECT_EQ(a.fused_sigma, b.fused_sigma);
  EXPECT_EQ(a.dead_band_factor, b.dead_band_factor);
  EXPECT_EQ(a.torque_alarm_samples, b.torque_alarm_samples);
  EXPECT_EQ(a.static_dead_band, b.static_dead_band);
  EXPECT_EQ(a.compensator_speed_limit, b.compensator_speed_limit);
  EXPECT_EQ(a.compensator_acceleration_limit, b.compensator_acceleration_limit);
  EXPECT_EQ(a.compensator_min_held_out_gain, b.compensator_min_held_out_gain);
}

class EstimatorParameterFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("tpf_estimator_file_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path path(const std::string& name) const { return dir_ / name; }

  /// The saved JSON of every_field_changed().
  Json saved() {
    const fs::path p = path("saved.json");
    tpf::save_estimator_parameters<4>(p, every_field_changed(), "test");
    std::ifstream in(p);
    return Json::parse(in);
  }

  /// The error message of loading `j` (written to `name`); "" when it loads.
  std::string load_error(const Json& j, const std::string& name = "bad.estimator.json") {
    std::ofstream(path(name)) << j.dump(2);
    try {
      tpf::load_estimator_parameters<4>(path(name));
    } catch (const tpf::Error& e) {
      return e.what();
    }
    return "";
  }

  fs::path dir_;
};

TEST_F(EstimatorParameterFile, EveryFieldSurvivesTheRoundTrip) {
  const Parameters written = every_field_changed();
  tpf::save_estimator_parameters<4>(path("a.json"), written, "calib.csv");
  const Parameters read = tpf::load_estimator_parameters<4>(path("a.json"));
  expect_same(written, read);
  // The fixture changes every saved field: no field round-trips only because it kept its default.
  tpf::save_estimator_parameters<4>(path("defaults.json"), Parameters{}, "");
  std::ifstream in(path("defaults.json"));
  const Json defaults = Json::parse(in).flatten(), changed = saved().flatten();
  for (const auto& [key, value] : defaults.items()) {
    if (key == "/format" || key == "/version" || key == "/joints" || key == "/torque_unit")
      continue;
    EXPECT_NE(value, changed.at(key)) << key << " keeps its default in the fixture";
  }

  // The defaults round-trip too (zero σ's, the default stop policy).
  expect_same(Parameters{}, tpf::load_estimator_parameters<4>(path("defaults.json")));
}

TEST_F(EstimatorParameterFile, EveryMissingFieldIsNamed) {
  // Remove each key of the saved file in turn (nested ones by their path).
  const Json full = saved();
  std::vector<std::vector<std::string>> keys;
  std::function<void(const Json&, std::vector<std::string>)> collect =
      [&](const Json& j, std::vector<std::string> at) {
        for (const auto& [key, value] : j.items()) {
          std::vector<std::string> path = at;
          path.push_back(key);
          keys.push_back(path);
          if (value.is_object()) collect(value, path);
        }
      };
  collect(full, {});
  ASSERT_GT(keys.size(), 30u);
  for (const auto& key : keys) {
    if (key.size() == 1 && key[0] == "source") continue;       // optional, for people
    if (key.size() == 1 && key[0] == "torque_unit") continue;  // optional: N·m is the only unit
    if (key.size() == 1 && key[0] == "compensator_min_held_out_gain") continue;  // optional
    Json j = full;
    Json* parent = &j;
    std::string name;
    for (std::size_t i = 0; i + 1 < key.size(); ++i) {
      parent = &(*parent)[key[i]];
      name += key[i] + ".";
    }
    parent->erase(key.back());
    name += key.back();
    const std::string e = load_error(j);
    EXPECT_NE(e.find("bad.estimator.json"), std::string::npos) << name << ": " << e;
    EXPECT_NE(e.find(name + ": missing"), std::string::npos) << name << ": " << e;
  }
}

TEST_F(EstimatorParameterFile, RefusesUnknownAndBadFieldsNamingThem) {
  const Json full = saved();
  Json j = full;
  j["skin"]["detector"]["on_level"] = 0.2;  // a typo of on_level_kpa
  EXPECT_NE(load_error(j).find("bad.estimator.json: skin.detector.on_level: unknown key"),
            std::string::npos)
      << load_error(j);
  j = full;
  j["dead_band"] = 1.5;
  EXPECT_NE(load_error(j).find("dead_band: unknown key"), std::string::npos) << load_error(j);
  j = full;
  j["nominal_sigma"][2] = -1.0;
  EXPECT_NE(load_error(j).find("nominal_sigma[2]: must be >= 0"), std::string::npos)
      << load_error(j);
  j = full;
  j["fused_sigma"] = {1.0, 2.0, 3.0};
  EXPECT_NE(load_error(j).find("fused_sigma: must be an array of 4 numbers"), std::string::npos)
      << load_error(j);
  j = full;
  j["skin"]["detector"]["off_level_kpa"] = 0.5;
  EXPECT_NE(load_error(j).find("skin.detector.off_level_kpa: must be below on_level_kpa"),
            std::string::npos)
      << load_error(j);
  j = full;
  j["static_friction"]["stop_policy"] = "hold";
  EXPECT_NE(load_error(j).find("static_friction.stop_policy: must be one of"), std::string::npos)
      << load_error(j);
  j = full;
  j["torque_alarm_samples"] = 0;
  EXPECT_NE(load_error(j).find("torque_alarm_samples: must be in [1,"), std::string::npos)
      << load_error(j);
  j = full;
  j["compensator_min_held_out_gain"] = 1.5;  // a gain is at most 1
  EXPECT_NE(load_error(j).find("compensator_min_held_out_gain: must be"), std::string::npos)
      << load_error(j);
  j = full;
  j.erase("compensator_min_held_out_gain");  // files calibrated before the gate: the default
  EXPECT_EQ(load_error(j), "");
  j = full;
  j["sample_period_s"] = 0.0;
  EXPECT_NE(load_error(j).find("sample_period_s: must be > 0"), std::string::npos) << load_error(j);
  j = full;
  j["joints"] = 6;
  EXPECT_NE(load_error(j).find("joints: the file is for 6 joints, the arm here has 4"),
            std::string::npos)
      << load_error(j);
  j = full;
  j["format"] = "tpf-params";
  EXPECT_NE(load_error(j).find("format: is 'tpf-params', expected 'tpf-estimator'"),
            std::string::npos)
      << load_error(j);
  j = full;
  j["version"] = 4;
  EXPECT_NE(load_error(j).find("version: is 4; this tpf reads up to version 3"), std::string::npos)
      << load_error(j);
  // Versions 1 and 2 hold σ's and bands in the nominal model's effort unit (mA): refused, naming
  // the field and the command that converts them.
  for (const int old : {1, 2}) {
    j = full;
    j["version"] = old;
    const std::string m = load_error(j);
    EXPECT_NE(m.find("version: is " + std::to_string(old) + ": "), std::string::npos) << m;
    EXPECT_NE(m.find("tpf upgrade"), std::string::npos) << m;
  }
  EXPECT_THROW(tpf::load_estimator_parameters<4>(path("no-such-file.json")), tpf::Error);
}

TEST(EstimatorParameterFileData, TheShippedArm4FileLoads) {
  // data/arm4.estimator.json: written by `tpf calibrate` from a SIMULATED calibration log.
  const Parameters p =
      tpf::load_estimator_parameters<4>(std::string(TPF_TEST_DATA_DIR) + "/arm4.estimator.json");
  // Calibrated: the transition σ's and dead bands are set (the defaults are 0).
  EXPECT_GT(p.nominal_sigma.minCoeff(), 0.0);
  EXPECT_GT(p.fused_sigma.minCoeff(), 0.0);
  EXPECT_GT(p.static_dead_band.minCoeff(), 0.0);
  EXPECT_GE(p.torque_alarm_samples, 1);
}

}  // namespace
