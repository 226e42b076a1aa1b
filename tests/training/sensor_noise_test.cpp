// The sensor noise read off a contact-free log (estimate_sensor_noise), against the σ the
// synthetic log was drawn with; a pad clipped at its 0 kPa rail must not bias the pads' σ low.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "offline/replay/replay_estimator.hpp"

namespace {

using tpf::offline::indexed_name;
using tpf::offline::Log;

/// A resting arm at 400 Hz: currents with σ = 6 mA (rounded to 1 mA), pad 1 at 0.2 kPa and pad 2
/// at −0.05 kPa (clipped at the 0 kPa rail: 95 % of its readings are 0), both with σ = 0.03 kPa.
Log resting_log() {
  constexpr Eigen::Index kRows = 8000;
  Log log;
  log.source = "synthetic.csv";
  log.meta.set("rate_hz", "400");
  std::mt19937 rng(3);
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::VectorXd t(kRows), zero = Eigen::VectorXd::Zero(kRows);
  for (Eigen::Index k = 0; k < kRows; ++k)
    t[k] = 0.0025 * static_cast<double>(k);
  log.values.resize(kRows, 0);
  log.add_column("t", t);
  for (int j = 1; j <= 4; ++j) {
    log.add_column(indexed_name("q", j), zero);
    log.add_column(indexed_name("dq", j), zero);
  }
  for (int j = 1; j <= 4; ++j) {
    Eigen::VectorXd i(kRows);
    for (Eigen::Index k = 0; k < kRows; ++k)
      i[k] = std::round(100.0 * j + 6.0 * normal(rng));
    log.add_column(indexed_name("i", j), i);
  }
  for (const double offset : {0.2, -0.05}) {
    Eigen::VectorXd p(kRows);
    for (Eigen::Index k = 0; k < kRows; ++k)
      p[k] = std::max(0.0, offset + 0.03 * normal(rng));
    log.add_column(indexed_name("p", log.pad_count() + 1), p);
  }
  return log;
}

TEST(SensorNoise, MatchesTheDrawnSigmaWithAPadOnItsRail) {
  // K_t = 1000 N·m/A: 1 mA reads as 1 N·m, so σ is in mA here.
  const tpf::offline::SensorNoise noise =
      tpf::offline::estimate_sensor_noise(resting_log(), Eigen::VectorXd::Constant(4, 1000.0));
  EXPECT_EQ(noise.effort_step, Eigen::VectorXd::Ones(4));
  for (int j = 0; j < 4; ++j)  // √(6² + 1/12): the 1 mA rounding adds a little
    EXPECT_NEAR(noise.effort[j], 6.0, 0.4) << "joint " << j + 1;
  // Pooling pad 2's repeated zeros with pad 1 would give ≈ 0.01 kPa.
  EXPECT_NEAR(noise.pad_kpa, 0.03, 0.003);
}

}  // namespace
