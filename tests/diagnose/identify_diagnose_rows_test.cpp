// One log, one held-out split: identify and diagnose (the library calls behind `tpf diagnose
// --identify-out`, and plain `tpf diagnose`) hold out the same rows of a several-file log whose
// files repeat one motion, decided once by decide_held_out_rows as the samples are extracted.
#include <gtest/gtest.h>

#include <filesystem>
#include <vector>

#include "offline/diagnose/diagnose.hpp"
#include "offline/identify/identification_setup.hpp"
#include "offline/log/log_writer.hpp"
#include "offline/log/read_logs.hpp"
#include "offline/samples/held_out_rows.hpp"
#include "offline/sim/scenario.hpp"
#include "offline/sim/simulate.hpp"
#include "support/arm_fixture.hpp"
#include "support/temp_dir.hpp"

namespace tpf::test {
namespace {

// Three twin files, the last repeating the first's motion (same scenario and seed): those two
// are held out together, the middle one is fitted on.
offline::Log files_with_a_repeat(const TempDir& dir) {
  const offline::Scenario scenario = offline::load_scenario(data_path("scenarios/excitation.json"));
  const offline::Log first = offline::simulate_to_log(scenario, 41, 30.0);
  offline::write_log(dir / "a.csv", first);
  offline::write_log(dir / "b.csv", offline::simulate_to_log(scenario, 42, 30.0));
  offline::write_log(dir / "c.csv", first);
  return offline::read_logs(
      std::vector<std::filesystem::path>{dir / "a.csv", dir / "b.csv", dir / "c.csv"});
}

TEST(IdentifyThenDiagnose, ScoresBothOnTheSameHeldOutRows) {
  TempDir dir("identify_diagnose_rows");
  const offline::Log log = files_with_a_repeat(dir);
  const offline::ModelX model = joint_count_cast<Eigen::Dynamic>(arm());
  const offline::DiagnoseOptions options;
  offline::IdentificationSetup setup = offline::prepare_diagnosis(log, model, options.samples);
  const tpf::BaseParameters base = setup.base;
  const auto regressors = setup.regressors;
  const auto abs_gravity = setup.abs_gravity;
  offline::IdentifyOptions identify_options;
  identify_options.samples = options.samples;
  const offline::Identification id =
      offline::identify(log, model, std::move(setup), identify_options);
  const offline::Diagnosis d =
      offline::diagnose(log, model, {id.samples, base, regressors, abs_gravity, nullptr}, options);

  // The first and last files repeat one motion: identify holds both out, not the last alone.
  const offline::JointSamples& s = id.samples;
  ASSERT_EQ(s.heldout_file_groups.size(), 2u);
  EXPECT_EQ(s.heldout_file_groups[s.heldout_group], (std::vector<std::size_t>{0, 2}));
  EXPECT_EQ(s.repeats.size(), 1u);
  EXPECT_EQ(s.heldout, offline::file_group_rows(log, {0, 2}));
  EXPECT_TRUE(id.refitted);
  // Not a vacuous comparison: the held-out rows carry moving samples on every joint.
  for (const offline::RegimeStats& joint : id.heldout)
    EXPECT_GT(joint[offline::Regime::Moving].count, 1000u);
  // Diagnose scores on those rows, and says so.
  EXPECT_EQ(d.samples.heldout, s.heldout);
  EXPECT_EQ(d.heldout_method, "by file: a.csv + c.csv");
  // Plain diagnose (its own reading of the samples) holds out the same rows.
  const offline::Diagnosis plain = offline::diagnose(log, model, options);
  EXPECT_EQ(plain.samples.heldout, s.heldout);
  EXPECT_EQ(plain.heldout_method, d.heldout_method);
}

}  // namespace
}  // namespace tpf::test
