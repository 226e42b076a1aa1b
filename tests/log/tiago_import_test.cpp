// The shipped TIAGo column map and imported log (data/real/tiago, MEASURED): three files joined
// by time, currents through signed torque constants and the gear ratios.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "offline/log/import_log.hpp"
#include "offline/log/read_log.hpp"
#include "offline/log/unit_check.hpp"

namespace tpf::offline {
namespace {

const std::string kTiago = std::string(TPF_TEST_DATA_DIR) + "/real/tiago";

TEST(TiagoImport, ShippedMapReproducesTheShippedLog) {
  const ImportMap map = load_import_map(kTiago + "/tiago.import.json");
  ImportReport report;
  const Log imported =
      import_log({kTiago + "/source/tiago_position.csv.gz",
                  kTiago + "/source/tiago_velocity.csv.gz", kTiago + "/source/tiago_effort.csv.gz"},
                 map, report);
  const Log shipped = read_log(kTiago + "/logs/tiago.csv.gz");
  ASSERT_EQ(imported.rows(), 8022);
  EXPECT_EQ(report.unmatched_rows, 0u);
  EXPECT_EQ(report.gap_steps, 0u);  // steps of 7.7–12.3 ms around 10 ms: irregular, no gap
  EXPECT_GT(report.irregular_steps, 600u);
  EXPECT_EQ(shipped.joint_count(), 8);
  EXPECT_EQ(shipped.effort_prefix(), "i");
  ASSERT_EQ(shipped.columns, imported.columns);
  EXPECT_TRUE(shipped.values.isApprox(imported.values, 1e-12));
}

TEST(TiagoImport, CurrentsAreInMilliampereWithTheOutputConstantsSign) {
  const Log log = read_log(kTiago + "/logs/tiago.csv.gz");
  // first row of tiago_effort.csv: 1.675, 0.032, 1.654, 0.056, 1.192, 0.0, 0.0, 0.0 (A);
  // kmotor of arm 3..7 is negative, so their currents change sign
  EXPECT_DOUBLE_EQ(log.col("i1")[0], 1675.0);
  EXPECT_DOUBLE_EQ(log.col("i3")[0], 1654.0);
  EXPECT_DOUBLE_EQ(log.col("i4")[0], -56.0);
  EXPECT_DOUBLE_EQ(log.col("i5")[0], -1192.0);
  // the torso is prismatic, in m: its first position 0.0598 m
  EXPECT_NEAR(log.col("q1")[0], 0.059777934162170615, 1e-15);
}

TEST(TiagoImport, TheWristCurrentsAreFlaggedDead) {
  const Log log = read_log(kTiago + "/logs/tiago.csv.gz");
  UnitCheckInput in;
  in.t = log.col("t");
  const auto family = [&](const char* prefix) {
    Eigen::MatrixXd m(log.rows(), 8);
    for (int j = 0; j < 8; ++j)
      m.col(j) = log.col(indexed_name(prefix, j + 1));
    return m;
  };
  in.q = family("q");
  in.dq = family("dq");
  in.effort = family("i");  // exact zeros and distinct values do not depend on K_t
  in.ddq = Eigen::MatrixXd::Constant(log.rows(), 8, std::nan(""));  // no rest is compared
  in.gravity = in.ddq;
  in.gear_ratio = Eigen::VectorXd::Ones(8);
  in.torque_constant = Eigen::VectorXd::Ones(8);
  in.lower = Eigen::VectorXd::Constant(8, -std::numeric_limits<double>::infinity());
  in.upper = -in.lower;
  const LogChecks checks = check_log_units(in);
  // arm 5, 6, 7: exact 0 in 88 %, 90 %, 90 % of the samples
  EXPECT_EQ(checks.dead_joints, (std::vector<int>{6, 7, 8}));
}

}  // namespace
}  // namespace tpf::offline
