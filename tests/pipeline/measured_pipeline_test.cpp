// The measured loop on the shipped Kinova Gen3 logs (MEASURED, data/real/kinova-gen3), held out
// by file, through the demo's stage 6 without the twin: the models beat K_t·i alone against the
// torque sensor by margins a broken fit misses, and the report and JSON hold those numbers. One
// test (ctest runs each test in its own process): the loop runs once.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "offline/measured_study/measured_report.hpp"
#include "offline/pipeline/demo_pipeline.hpp"
#include "support/page_structure.hpp"

namespace tpf::offline {
namespace {

std::string read_measured_text(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

double column_rmse(const MeasuredSplit& split, const std::string& column, int joint) {
  const int c = measured_column(split, column);
  EXPECT_GE(c, 0) << column;
  return c < 0 ? NAN
               : split.columns[static_cast<std::size_t>(c)].rmse[static_cast<std::size_t>(joint)];
}

void expect_models_beat_kt_only(const MeasuredSplit& f) {
  EXPECT_EQ(f.scored_on, "opti_traj_testing1.csv.gz + opti_traj_testing2.csv.gz");
  for (int j = 0; j < 6; ++j) {
    const double kt = column_rmse(f, "Kt only", j);
    // The maker's TorqueCur is K_t·Cur exactly: the same RMSE.
    EXPECT_NEAR(column_rmse(f, "maker (tau_maker)", j), kt, 1e-3 * kt) << "joint " << j + 1;
    EXPECT_GT(kt, 1.0) << "joint " << j + 1;
    // Friction fitted against the sensor: at least 40 % below K_t·i alone on every joint (50–83 %
    // measured); a model without friction stays at K_t·i's error.
    EXPECT_LT(column_rmse(f, "friction against the sensor", j), 0.6 * kt) << "joint " << j + 1;
    EXPECT_LT(column_rmse(f, "+ current low-pass", j), 0.7 * kt) << "joint " << j + 1;
  }
  // The current-based identification halves the error where the rigid body matters little.
  for (int j : {0, 4, 5})
    EXPECT_LT(column_rmse(f, "after identification", j), 0.5 * column_rmse(f, "Kt only", j))
        << "joint " << j + 1;
  EXPECT_TRUE(std::isnan(column_rmse(f, "Kt only", 6))) << "joint 7's sensor is flat: not scored";
}

void expect_claims_only_where_the_heldout_error_falls(const std::vector<SensorCandidate>& all) {
  int claimed = 0;
  for (const SensorCandidate& c : all) {
    ASSERT_TRUE(std::isfinite(c.heldout_before) && std::isfinite(c.heldout_after)) << c.key;
    if (!c.supported) continue;
    ++claimed;
    EXPECT_LE(c.heldout_after, 0.95 * c.heldout_before) << c.key << " joint " << c.joint + 1;
  }
  EXPECT_GT(claimed, 0);
  EXPECT_LT(claimed, static_cast<int>(all.size()));
}

void expect_facts_from_the_files(const MeasuredFacts& facts) {
  ASSERT_EQ(facts.files.size(), 5u);
  for (const MeasuredFile& f : facts.files) {
    EXPECT_GT(f.seconds, 1.5) << f.name;
    EXPECT_LT(f.seconds, 5.5) << f.name;
    EXPECT_FALSE(f.sensor_usable[6]) << f.name << ": joint 7's sensor is flat";
    for (int r : f.reversals)
      EXPECT_LE(r, 2) << f.name;
  }
  EXPECT_EQ(facts.files[1].name, "Trajectory1.csv.gz");
  EXPECT_FALSE(facts.files[1].sensor_usable[0]) << "Trajectory1's sensor columns are all 0";
  ASSERT_EQ(facts.repeats.size(), 1u) << "Trajectory1 repeats RunTrajectory1's motion";
  EXPECT_EQ(facts.repeats[0].first, 0u);
  EXPECT_EQ(facts.repeats[0].second, 1u);
}

void expect_report_and_json(const std::filesystem::path& out, const MeasuredResult& r) {
  const std::string html = read_measured_text(out / "measured.html");
  EXPECT_NE(html.find("MEASURED DATA"), std::string::npos);
  EXPECT_NE(html.find("W. Chiha, MIT licence"), std::string::npos);
  EXPECT_NE(html.find("data/real/kinova-gen3/SOURCE.md"), std::string::npos);
  EXPECT_NE(html.find("<svg"), std::string::npos);
  EXPECT_NE(read_measured_text(out / "index.html").find("href=\"measured.html\""),
            std::string::npos);
  // Both pages lead with the per-joint figure, keep their paragraphs short and stay light.
  EXPECT_EQ(test::page_problems(html), "");
  EXPECT_EQ(test::page_problems(read_measured_text(out / "index.html")), "");
  EXPECT_EQ(test::leading_element(html), "figure");
  const auto json = nlohmann::json::parse(read_measured_text(out / "measured.json"));
  EXPECT_TRUE(json.at("measured").get<bool>());
  const int c = measured_column(r.forward, "friction against the sensor");
  ASSERT_GE(c, 0);
  const auto& column = json.at("forward").at("columns").at(static_cast<std::size_t>(c));
  EXPECT_EQ(column.at("name"), "friction against the sensor");
  for (std::size_t j = 0; j < 6; ++j)
    EXPECT_DOUBLE_EQ(column.at("rmse_newton_metre").at(j).get<double>(),
                     r.forward.columns[static_cast<std::size_t>(c)].rmse[j]);
  EXPECT_TRUE(column.at("rmse_newton_metre").at(6).is_null());
  EXPECT_EQ(json.at("candidates").size(), r.candidates.size());
}

// The floor: the best memoryless model's residual above 20 Hz is the current's noise (its own d
// has a fraction of it there), and on joints 1, 3, 5 it leaves less than the compensator target's
// 30 % to gain (measured 12.9–21.9 %); on joints 2, 4, 6 it leaves 39–61 %.
void expect_noise_floor(const std::filesystem::path& out, const MeasuredFloor& f) {
  ASSERT_EQ(f.best_rmse.size(), 7u);
  EXPECT_EQ(f.cutoff_hz, 20.0);
  for (std::size_t j = 0; j < 6; ++j) {
    EXPECT_GT(f.floor[j], 0.3 * f.best_rmse[j]) << "joint " << j + 1;
    EXPECT_LT(f.floor[j], f.best_rmse[j]) << "joint " << j + 1;
    EXPECT_LT(f.model_high[j], 0.5 * f.floor[j]) << "joint " << j + 1;
    EXPECT_TRUE(std::isnan(f.compensator_rmse[j])) << "no compensator trained here";
  }
  for (std::size_t j : {0u, 2u, 4u})
    EXPECT_LT(1.0 - f.floor[j] / f.best_rmse[j], f.target) << "joint " << j + 1;
  for (std::size_t j : {1u, 3u, 5u})
    EXPECT_GT(1.0 - f.floor[j] / f.best_rmse[j], f.target) << "joint " << j + 1;
  EXPECT_TRUE(std::isnan(f.best_rmse[6])) << "joint 7's sensor is flat";
  const auto json = nlohmann::json::parse(read_measured_text(out / "measured.json"));
  const auto& joints = json.at("compensator_floor").at("joints");
  ASSERT_EQ(joints.size(), 7u);
  EXPECT_DOUBLE_EQ(joints.at(1).at("floor_rmse").get<double>(), f.floor[1]);
  EXPECT_FALSE(joints.at(0).at("target_reachable").get<bool>());
  EXPECT_NE(read_measured_text(out / "measured.html").find("noise floor"), std::string::npos);
}

// What bounds the held-out error: the bound's own scoring agrees with validate's columns, and on
// joint 2 it says why 60 % is missed held out: the fitting files never move it backwards, the
// same model class fitted on the scored files stays above the target unfiltered and reaches it
// only with the current low-passed; held out, the error between 2 and 20 Hz is the largest part,
// and the time constant the fitting files choose makes it worse on the scored files. In the
// reverse split the current carries an oscillation between 2 and 20 Hz that the sensor does not
// show.
void expect_bound(const std::filesystem::path& out, const MeasuredResult& r) {
  const MeasuredBound& b = r.bound;
  ASSERT_EQ(b.maker.size(), 7u);
  for (int j = 0; j < 6; ++j) {
    const std::size_t k = static_cast<std::size_t>(j);
    EXPECT_NEAR(b.maker[k], column_rmse(r.forward, "Kt only", j), 1e-9) << "joint " << j + 1;
    EXPECT_NEAR(b.heldout[k], column_rmse(r.forward, "friction against the sensor", j), 1e-9);
    EXPECT_NEAR(b.heldout_low_pass[k], column_rmse(r.forward, "+ current low-pass", j), 1e-9);
    EXPECT_DOUBLE_EQ(b.fit_time_constants[j], r.low_pass_time_constants[j]);
    EXPECT_NEAR(b.target[k], 0.4 * b.maker[k], 1e-12);
    // The oracles see the scored files: never worse than what they start from.
    EXPECT_LE(b.oracle_low_pass[k], b.heldout[k] + 1e-12) << "joint " << j + 1;
    EXPECT_LE(b.oracle_low_pass[k], b.heldout_low_pass[k] + 1e-12) << "joint " << j + 1;
    EXPECT_LE(b.in_sample_low_pass[k], b.in_sample[k] + 1e-12) << "joint " << j + 1;
    EXPECT_NEAR(b.band_low[k] * b.band_low[k] + b.band_mid[k] * b.band_mid[k] +
                    b.band_high[k] * b.band_high[k],
                b.heldout[k] * b.heldout[k], 1e-9);
  }
  // Joint 2 (demo: held out 3.699, target 3.163, in-sample 3.327 and low-passed 2.863; held out
  // below 2 Hz 2.151, 2–20 Hz 2.523, above 20 Hz 1.640; the fitting files' 100 ms 3.827, the
  // scored files' best, 50 ms, 3.140).
  EXPECT_GT(b.fit_velocity_min[1], -0.1) << "the fitting files move joint 2 one way";
  EXPECT_GT(b.velocity_samples[1], 0.6);
  EXPECT_GT(b.velocity_error[1], 0.4);
  EXPECT_GT(b.heldout[1], b.target[1]);
  EXPECT_GT(b.in_sample[1], 0.98 * b.target[1]);
  EXPECT_LT(b.in_sample[1], b.heldout[1]);
  EXPECT_LT(b.in_sample_low_pass[1], b.target[1]);
  EXPECT_GT(b.band_mid[1], b.band_low[1]) << "2–20 Hz holds more of the error than below 2 Hz";
  EXPECT_GT(b.band_mid[1], b.band_high[1]);
  EXPECT_GT(b.heldout_low_pass[1], b.heldout[1]) << "the fitting files' time constant (100 ms) "
                                                    "does not transfer";
  EXPECT_LT(b.oracle_low_pass[1], b.heldout_low_pass[1]);
  // The load terms of the friction are scored beside it (their own fit, so a different RMSE).
  ASSERT_EQ(b.heldout_without_load.size(), 7u);
  EXPECT_NE(b.heldout_without_load[1], b.heldout[1]);
  EXPECT_LT(std::abs(b.heldout_without_load[1] / b.heldout[1] - 1.0), 0.2);
  // Reverse (RunTrajectory1 + RecordTrajectory_quadratic scored): K_t·i 4.1 N·m between 2 and
  // 20 Hz on joint 2, the sensor 0.19; that band holds 45 % of the held-out squared error.
  const MeasuredBound& rb = r.reverse_bound;
  ASSERT_EQ(rb.maker.size(), 7u);
  EXPECT_GT(rb.current_mid[1], 10 * rb.sensor_mid[1]);
  EXPECT_GT(rb.current_mid[1], 3.0);
  EXPECT_GT(rb.band_mid[1] * rb.band_mid[1], 0.3 * rb.heldout[1] * rb.heldout[1]);
  const auto json = nlohmann::json::parse(read_measured_text(out / "measured.json"));
  EXPECT_DOUBLE_EQ(json.at("bound").at("in_sample_rmse").at(1).get<double>(), b.in_sample[1]);
  EXPECT_TRUE(json.at("reverse_bound").at("maker_rmse").at(6).is_null());
  const std::string html = read_measured_text(out / "measured.html");
  EXPECT_NE(html.find("What bounds the held-out error"), std::string::npos);
  EXPECT_NE(html.find("joint 2: the drive loss the sensor sees"), std::string::npos);
}

TEST(MeasuredLoop, BeatsKtOnlyHeldOutByFileAndReportsIt) {
  DemoOptions o;
  o.out =
      std::filesystem::temp_directory_path() / ("tpf_measured_loop_" + std::to_string(::getpid()));
  o.run_twin = false;
  o.run_tiago = false;              // the TIAGo log: TiagoStudy
  o.measured.run_diagnose = false;  // diagnose and train have their own tests; keep this short
  o.measured.run_training = false;
  o.measured.run_reverse = false;
  o.measured.friction_samples_per_joint = 300;
  const DemoResult result = run_demo(o);
  ASSERT_TRUE(result.measured.has_value());
  const MeasuredResult& r = *result.measured;
  expect_models_beat_kt_only(r.forward);
  expect_claims_only_where_the_heldout_error_falls(r.candidates);
  expect_facts_from_the_files(r.facts);
  expect_report_and_json(o.out, r);
  expect_noise_floor(o.out, r.floor);
  expect_bound(o.out, r);
  std::filesystem::remove_all(o.out);
}

TEST(MeasuredReport, AnEffectOnEveryJointIsJudgedByItsSummedError) {
  // A payload lowers joint 2 a little and raises joint 1: its summed squared error falls
  // (100² + 1000² → 110² + 900²), so it is listed as lowering the error, with both joints named;
  // a spring on joint 2 alone that raises it is listed as raising it.
  MeasuredResult r;
  r.diagnosis_effort = {{"after identification", {100, 1200}},
                        {"diagnose's declared model", {100, 1000}},
                        {"+ payload (folded into the rigid body)", {110, 900}},
                        {"+ spring, joint 2", {110, 950}}};
  const std::string s = diagnosis_transfer_sentence(r);
  EXPECT_NE(
      s.find("lower the error: payload (folded into the rigid body) (−18.6\u00a0% of the squared "
             "error summed over the joints: lowers joint 2 −10.0\u00a0%; raises joint 1 "
             "+10.0\u00a0%)"),
      std::string::npos)
      << s;
  EXPECT_NE(s.find("not claimed here: spring, joint 2 (joint 2 +5.6\u00a0%)"), std::string::npos)
      << s;
}

TEST(MeasuredReport, TheOracleCompensatorClosesATargetTheFloorLeavesOpen) {
  // Joint 1: floor 1.8 of 2.0 N·m leaves 10 % (< 30 %): closed by the floor. Joint 2: floor 1.6
  // of 3.5 leaves 54 %, but the compensator trained on the scored files reaches only 3.4 (−2.9 %):
  // closed by the oracle. Joint 3: room and an oracle at 2.0 of 3.0 (−33.3 %): open, and said.
  MeasuredFloor f;
  f.target = 0.3;
  f.best_rmse = {2.0, 3.5, 3.0};
  f.floor = {1.8, 1.6, 1.0};
  f.oracle_compensator_rmse = {1.9, 3.4, 2.0};
  f.cutoff_hz = 20.0;
  f.best_name = {"a", "b", "c"};
  f.compensator_rmse = {2.1, 3.6, 2.9};
  f.model_high = {0.1, 0.1, 0.1};
  const std::string s = compensator_floor_sentence(f);
  EXPECT_NE(s.find("on joints 2, 3 and none on joints 1:"), std::string::npos) << s;
  EXPECT_NE(s.find("still falls short (joint 2 −2.9\u00a0% against"), std::string::npos) << s;
  EXPECT_EQ(s.find("falls short (joint 2 −2.9\u00a0%, joint 3"), std::string::npos) << s;
  // Joint 3's oracle reaches the target, the compensator held out (2.9, −3.3 %) does not.
  EXPECT_NE(s.find("reaches the target on joint 3 −33.3\u00a0% (held out −3.3\u00a0%)"),
            std::string::npos)
      << s;
  const Table t = compensator_floor_table(f);
  ASSERT_EQ(t.rows.size(), 3u);
  EXPECT_EQ(t.rows[1][4], "3.400 (−2.9\u00a0%)");
}

}  // namespace
}  // namespace tpf::offline
