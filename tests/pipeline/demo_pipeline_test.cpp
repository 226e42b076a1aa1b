// The whole loop on very short twin logs (SIMULATED): every stage runs and writes its outputs.
#include "offline/pipeline/demo_pipeline.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "offline/replay/replay_estimator.hpp"
#include "support/page_structure.hpp"
#include "support/temp_dir.hpp"
#include "tpf/estimation/estimator_parameter_file.hpp"
#include "tpf/estimation/nominal_model.hpp"
#include "tpf/nn/load_tcn_weights.hpp"

namespace tpf::offline {
namespace {

std::string read_text(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(DemoPipeline, ShortLogsRunEveryStageAndWriteTheReport) {
  const test::TempDir dir("demo_pipeline");  // per process: two runs at once do not share it
  DemoOptions o;
  o.out = dir.path();
  o.training_s = 30.0;
  o.calibration_s = 10.0;
  o.test_s = 10.0;
  o.contacts_s = 12.0;
  o.teaching_s = 6.0;
  o.training_epochs = 2;
  o.run_measured = false;  // the Kinova logs: MeasuredLoop
  o.run_tiago = false;     // the TIAGo log: TiagoStudy
  std::vector<std::string> lines;
  const DemoResult r = run_demo(o, [&](const std::string& l) { lines.push_back(l); });

  for (const char* stage :
       {"[1/7] simulate", "[2/7] identify", "[3/7] diagnose", "[4/7] train", "[5/7] evaluate"}) {
    EXPECT_TRUE(std::any_of(lines.begin(), lines.end(), [&](const std::string& l) {
      return l.rfind(stage, 0) == 0;
    })) << stage;
  }
  const std::string index = read_text(o.out / "index.html");
  EXPECT_NE(index.find("href=\"evaluate.html\""), std::string::npos);
  EXPECT_NE(index.find("href=\"diagnose.html\""), std::string::npos);
  EXPECT_NE(index.find("SIMULATED"), std::string::npos);
  EXPECT_NE(read_text(o.out / "evaluate.html").find("SIMULATED"), std::string::npos);
  EXPECT_NE(read_text(o.out / "diagnose.html").find("SIMULATED"), std::string::npos);
  // Each page reads at a glance: it leads with a figure or a table, short paragraphs, light,
  // no words of its making; the entry page shows Table I and the diagnosis before any click.
  for (const char* page : {"index.html", "diagnose.html", "evaluate.html"})
    EXPECT_EQ(test::page_problems(read_text(o.out / page)), "") << page;
  EXPECT_GE(test::figures_before_details(index), 2);
  EXPECT_NE(index.find("<th>why</th>"), std::string::npos);

  const auto json = nlohmann::json::parse(read_text(o.out / "evaluation.json"));
  EXPECT_TRUE(json.at("simulated").get<bool>());
  EXPECT_EQ(json.at("residual_table").size(), 15u);  // (4 joints + all) × 3 regimes
  EXPECT_GT(json.at("detection").at("tactile-only").at("events").get<int>(), 0);

  // The written files load into the run-time estimator of the arm (4 joints, 11 pads, one
  // 16-channel network per joint), as a controller loads them.
  const std::string data = TPF_TEST_DATA_DIR;
  const auto estimator = load_estimator<4, 11, PerJointTcn<BFloat16Weights, 16>>(
      {(o.out / "nominal.params.json").string(), data + "/arm4.robot.json",
       data + "/arm4.pads.json", (o.out / "arm4.estimator.json").string(),
       (o.out / "tcn.json").string()});
  // The run-time loop's estimator parameters (N·m), as the demo calibrated them (its report
  // shows them in the log's mA).
  const auto& p = estimator->parameters();
  const auto& c = r.evaluation.calibration;
  EXPECT_STREQ(r.evaluation.units.name(), "mA");
  for (int j = 0; j < 4; ++j) {
    EXPECT_NEAR(r.evaluation.units.to_effort(j, p.nominal_sigma[j]), c.sigma_nominal[j],
                1e-9 * c.sigma_nominal[j]);
    EXPECT_NEAR(r.evaluation.units.to_effort(j, p.fused_sigma[j]), c.sigma_fused[j],
                1e-9 * c.sigma_fused[j]);
  }
  EXPECT_EQ(p.torque_alarm_samples, r.evaluation.calibration.torque_alarm_samples);
  ASSERT_EQ(r.training.results.size(), 4u);
  for (const auto& t : r.training.results)
    EXPECT_LE(t.history.size(), 2u);
}

}  // namespace
}  // namespace tpf::offline
