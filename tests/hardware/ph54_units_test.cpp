// PH54 unit conversions (hardware.md §2.5) and the loop statistics used in the report.
#include <gtest/gtest.h>

#include <numbers>

#include "arm/excitation.hpp"
#include "arm/loop_statistics.hpp"
#include "dynamixel/ph54/control_table.hpp"
#include "dynamixel/ph54/units.hpp"

namespace tpf {
namespace {

TEST(Ph54Units, MatchTheControlTableUnits) {
  using namespace dxl::ph54;
  EXPECT_NEAR(position_to_rad(501'923), std::numbers::pi, 1e-12);  // ±501,923 ↔ ±180°
  EXPECT_NEAR(kRadPerPulse, 6.259113e-6, 1e-12);
  EXPECT_NEAR(position_to_rad(-125'480) * 180.0 / std::numbers::pi, -45.0, 1e-3);  // PAPRAS joint 3
  EXPECT_EQ(rad_to_position(std::numbers::pi / 2), 250'962);  // 250,961.5 rounds up
  EXPECT_NEAR(velocity_to_rad_s(1), 1.0471976e-3, 1e-10);     // 0.01 rev/min
  EXPECT_EQ(rad_s_to_velocity(velocity_to_rad_s(2920)), 2920);
  EXPECT_DOUBLE_EQ(current_to_ampere(-1500), -1.5);
  EXPECT_EQ(ampere_to_current(40.0), 32767);  // saturates at the int16 range
  EXPECT_DOUBLE_EQ(voltage_to_volt(240), 24.0);
  EXPECT_EQ(baud_rate_of(BaudCode::b4M), 4'000'000);
}

TEST(LoopStatistics, PercentilesAndMax) {
  arm::LoopStatistics stats(1000);
  for (int k = 1; k <= 100; ++k)
    stats.record(k * 1e-6, 2 * k * 1e-6);
  const arm::TimingSummary s = stats.summarize();
  EXPECT_EQ(s.cycles, 100u);
  EXPECT_NEAR(s.lateness_p50_s, 51e-6, 1e-12);  // nearest rank of 0.5·99 = 49.5 → index 50
  EXPECT_NEAR(s.lateness_p99_s, 99e-6, 1e-12);
  EXPECT_NEAR(s.lateness_max_s, 100e-6, 1e-12);
  EXPECT_NEAR(s.bus_max_s, 200e-6, 1e-12);
}

TEST(LoopStatistics, KeepsTheLastWindowButTheOverallMax) {
  arm::LoopStatistics stats(10);
  stats.record(1.0, 0.0);  // overwritten in the window, still the max
  for (int k = 0; k < 20; ++k)
    stats.record(1e-3, 0.0);
  const arm::TimingSummary s = stats.summarize();
  EXPECT_EQ(s.cycles, 21u);
  EXPECT_DOUBLE_EQ(s.lateness_p99_s, 1e-3);
  EXPECT_DOUBLE_EQ(s.lateness_max_s, 1.0);
}

TEST(Excitation, RampsInAndStaysWithinAmplitude) {
  EXPECT_DOUBLE_EQ(arm::excitation_goal(0, 0.0, 0.3, 0.5), 0.5);
  double peak = 0.0;
  for (int k = 0; k < 40000; ++k) {
    const double t = k * 0.0025;
    peak = std::max(peak, std::abs(arm::excitation_goal(2, t, 0.3, 0.0)));
  }
  EXPECT_LE(peak, 0.3 + 1e-12);
  EXPECT_GT(peak, 0.2);  // the three sines add up to a large fraction of A within 100 s
}

}  // namespace
}  // namespace tpf
