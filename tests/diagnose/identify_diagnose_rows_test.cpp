// One log, one held-out split: identify and diagnose (the library calls behind `tpf diagnose
// --identify-out`, and behind plain `tpf diagnose`) hold out the same rows, decided once by
// decide_held_out_rows, and diagnose scores identify's declared model there with identify's own
// figures instead of refitting it.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <vector>

#include "offline/diagnose/diagnose.hpp"
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

// Every regime's held-out count and RMSE of `b` equal `a`'s, joint by joint (both NaN where a
// regime has no sample).
void expect_same_scores(const std::vector<offline::RegimeStats>& a,
                        const std::vector<offline::RegimeStats>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t j = 0; j < a.size(); ++j)
    for (std::size_t r = 0; r < a[j].by_regime.size(); ++r) {
      EXPECT_EQ(a[j].by_regime[r].count, b[j].by_regime[r].count) << "joint " << j + 1;
      const double x = a[j].by_regime[r].rmse, y = b[j].by_regime[r].rmse;
      EXPECT_TRUE(x == y || (std::isnan(x) && std::isnan(y)))  // NaN: no sample in that regime
          << "joint " << j + 1 << ": " << x << " against " << y;
    }
}

TEST(IdentifyThenDiagnose, ScoresBothOnTheSameHeldOutRows) {
  TempDir dir("identify_diagnose_rows");
  const offline::Log log = files_with_a_repeat(dir);
  const offline::ModelX model = joint_count_cast<Eigen::Dynamic>(arm());
  const offline::DiagnoseOptions options;
  offline::IdentifiedLog identified =
      offline::identify_for_diagnosis(log, model, offline::identify_options_of(options));
  const offline::Identification id = identified.identification;  // diagnose takes the samples
  const offline::Diagnosis d = offline::diagnose(log, model, std::move(identified), options);

  // The first and last files repeat one motion: identify holds both out, not the last alone.
  const offline::JointSamples& s = id.samples;
  ASSERT_EQ(s.heldout_file_groups.size(), 2u);
  EXPECT_EQ(s.heldout_file_groups[s.heldout_group], (std::vector<std::size_t>{0, 2}));
  EXPECT_EQ(s.repeats.size(), 1u);
  EXPECT_EQ(s.heldout, offline::file_group_rows(log, {0, 2}));
  EXPECT_TRUE(id.refitted);
  EXPECT_EQ(d.samples.heldout, s.heldout);
  EXPECT_EQ(d.heldout_method, "by file: a.csv + c.csv");

  // Diagnose's declared model is identify's fit on the training rows, scored on the same rows
  // with the same figures, and its fits keep identify's weights and prior strength.
  EXPECT_EQ(d.declared.base_values, id.judged.base_values);
  EXPECT_EQ(d.declared.friction.coulomb, id.judged.friction.coulomb);
  expect_same_scores(d.written_before, id.heldout);
  EXPECT_EQ(d.inertia_prior_strength, id.inertia_prior.written_strength);
  // Not a vacuous comparison: the held-out rows carry moving samples on every joint.
  for (const offline::RegimeStats& joint : id.heldout)
    EXPECT_GT(joint[offline::Regime::Moving].count, 1000u);

  // Plain diagnose (no identification handed over) identifies the same way first.
  const offline::Diagnosis plain = offline::diagnose(log, model, options);
  EXPECT_EQ(plain.samples.heldout, s.heldout);
  expect_same_scores(plain.written_before, id.heldout);
  EXPECT_EQ(plain.nominal.base_values, d.nominal.base_values);
}

}  // namespace
}  // namespace tpf::test
