// The shipped Kinova Gen3 column map and imported logs (data/real/kinova-gen3, MEASURED).
#include <gtest/gtest.h>

#include <string>

#include "log_test_files.hpp"
#include "offline/log/import_log.hpp"
#include "offline/log/read_log.hpp"
#include "offline/log/torque_sensor.hpp"

namespace tpf::offline {
namespace {

using test::TempDir;
using test::write_text;

const std::string kKinova = std::string(TPF_TEST_DATA_DIR) + "/real/kinova-gen3";

/// A Kinova CSV header (78 columns) and two rows: joint j's values are j + the column's base.
std::string kinova_excerpt() {
  const char* families[] = {"Position",      "Velocity", "Torque",     "TorqueSm",
                            "TorqueCur",     "Temp",     "Cur",        "PositionCmptd",
                            "VelocityCmptd", "AccCmptd", "TorqueCmptd"};
  std::string text = "Time";
  for (const char* f : families)
    for (int j = 1; j <= 7; ++j)
      text.append(",").append(f).append(std::to_string(j));
  text += "\n";
  for (int row = 0; row < 2; ++row) {
    text += std::to_string(row);
    for (int f = 0; f < 11; ++f)
      for (int j = 1; j <= 7; ++j)
        text.append(",").append(std::to_string(10 * f + j + 0.5 * row));
    text += "\n";
  }
  return text;
}

TEST(KinovaImport, ShippedMapTakesTheRightColumnsInTheRightUnits) {
  TempDir dir("kinova_map");
  write_text(dir / "k.csv", kinova_excerpt());
  const ImportMap map = load_import_map(kKinova + "/kinova.import.json");
  ImportReport report;
  const Log log = import_log(dir / "k.csv", map, report);
  ASSERT_EQ(log.rows(), 2);
  EXPECT_DOUBLE_EQ(log.col("t")[1], 0.001);           // sample index at 1 kHz
  EXPECT_DOUBLE_EQ(log.col("q3")[0], 3.0);            // Position3 [rad]
  EXPECT_DOUBLE_EQ(log.col("dq5")[1], 15.5);          // Velocity5
  EXPECT_DOUBLE_EQ(log.col("tau_sensor2")[0], 22.0);  // Torque2 [N·m]
  EXPECT_DOUBLE_EQ(log.col("tau_maker7")[0], 47.0);   // TorqueCur7
  EXPECT_DOUBLE_EQ(log.col("temp1")[1], 51.5);        // Temp1 [°C]
  EXPECT_DOUBLE_EQ(log.col("i4")[0], 64000.0);        // Cur4 = 64 A → mA
  EXPECT_FALSE(log.has("AccCmptd1"));
  EXPECT_EQ(log.meta.get("robot"), "kinova-gen3");
}

TEST(KinovaImport, ShippedLogReadsWithItsFlatSensorsNamed) {
  const Log log = read_log(kKinova + "/logs/Trajectory1.csv.gz");
  EXPECT_EQ(log.rows(), 1942);
  EXPECT_EQ(log.joint_count(), 7);
  EXPECT_EQ(log.effort_prefix(), "i");
  EXPECT_EQ(log.quality.gaps, 0u);
  const auto report = torque_sensor_report(log, 7);
  ASSERT_EQ(report.size(), 1u);
  EXPECT_NE(report[0].find("flat (range < 0.05 N*m) on joints 1-7"), std::string::npos)
      << report[0];
}

}  // namespace
}  // namespace tpf::offline
