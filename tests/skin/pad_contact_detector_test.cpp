// Contact detection on one pad: hysteresis without chatter, onset time, release, drift.
#include "tpf/skin/pad_contact_detector.hpp"

#include <gtest/gtest.h>

#include <random>

#include "support/constants.hpp"

namespace {

using tpf::test::kPeriod;
constexpr double kNoise = 0.03;  // kPa, the twin's pad noise

tpf::PadDetectorSettings<double> settings() {
  return tpf::detector_settings_from_noise(kNoise, kPeriod, 0.0105);
}

TEST(PadContactDetector, LevelsFromNoise) {
  const auto s = settings();
  const double filtered =
      kNoise * tpf::low_pass_noise_gain(tpf::low_pass_coefficient(40.0, kPeriod));
  EXPECT_NEAR(s.off_level_kpa, 4 * filtered, 1e-12);
  EXPECT_NEAR(s.on_level_kpa, 8 * filtered, 1e-12);
  // A noise below the ADC resolution falls back to whole steps.
  const auto q = tpf::detector_settings_from_noise(1e-4, kPeriod, 0.0105);
  EXPECT_DOUBLE_EQ(q.off_level_kpa, 0.0105);
  EXPECT_DOUBLE_EQ(q.on_level_kpa, 0.021);
}

TEST(PadContactDetector, NoiseAndDriftNeverSwitchItOn) {
  std::mt19937_64 rng(11);
  std::normal_distribution<double> noise(0.0, 1.0);
  tpf::PadContactDetector<double> d(settings());
  double offset = 0.4;
  d.reset(0.0, offset);
  int switches = 0;
  for (int k = 1; k < 400 * 300; ++k) {                // 5 minutes
    offset += 0.01 * std::sqrt(kPeriod) * noise(rng);  // the twin's drift, 0.01 kPa/√s
    d.update(k * kPeriod, offset + kNoise * noise(rng), kPeriod);
    switches += d.changed();
  }
  EXPECT_EQ(switches, 0);
}

TEST(PadContactDetector, HysteresisDoesNotChatterWhereOneThresholdWould) {
  // Load hovering between the off and on levels after one real onset, with noise smaller than the
  // hysteresis band (σ_f = (on − off)/16): one threshold at the midpoint chatters, the hysteresis
  // stays on.
  std::mt19937_64 rng(5);
  std::normal_distribution<double> noise(0.0, 1.0);
  const auto s = settings();
  tpf::PadContactDetector<double> d(s);
  d.reset(0.0, 0.0);
  const double hover = 0.5 * (s.on_level_kpa + s.off_level_kpa);
  int switches = 0, single_threshold_switches = 0;
  bool single = false;
  double filtered = 0;
  for (int k = 1; k < 4000; ++k) {
    const double load = k < 40 ? 0.4 * k / 40.0 : (k < 80 ? 0.4 : hover);
    const double p = load + 0.25 * kNoise * noise(rng);
    d.update(k * kPeriod, p, kPeriod);
    switches += d.changed();
    filtered = d.filtered_kpa();
    const bool now = filtered > hover;
    single_threshold_switches += now != single;
    single = now;
  }
  EXPECT_EQ(switches, 1);  // the onset only
  EXPECT_GT(single_threshold_switches, 50);
}

TEST(PadContactDetector, OnsetTimeIsWhenThePressureLeftTheNoiseBand) {
  const auto s = settings();
  tpf::PadContactDetector<double> d(s);
  d.reset(0.0, 0.2);
  const double t0 = 1.0;  // the push begins: 2 kPa/s ramp (≈ 1.3 N/s on a 1.5 kPa/N pad)
  double detected = -1;
  for (int k = 1; k < 800; ++k) {
    const double t = k * kPeriod;
    const double p = 0.2 + (t > t0 ? 2.0 * (t - t0) : 0.0);
    if (d.update(t, p, kPeriod) && detected < 0) detected = t;
  }
  ASSERT_GT(detected, 0);
  EXPECT_GT(detected, t0 + 0.05);  // the on level (≈ 0.135 kPa) takes ≈ 0.07 s of the ramp
  EXPECT_GE(d.onset_time(), t0 - kPeriod);
  EXPECT_LE(d.onset_time(), t0 + s.off_level_kpa / 2.0 + 0.01);  // off level + filter lag
  EXPECT_LT(d.onset_time(), detected - 0.02);
}

TEST(PadContactDetector, ReleaseBelowTheOffLevelAndOffsetFrozenDuringContact) {
  const auto s = settings();
  tpf::PadContactDetector<double> d(s);
  d.reset(0.0, 1.0);
  int k = 1;
  for (; k < 200; ++k)
    d.update(k * kPeriod, 3.0, kPeriod);  // 2 kPa push for 0.5 s
  EXPECT_TRUE(d.in_contact());
  EXPECT_DOUBLE_EQ(d.offset_kpa(), 1.0);
  EXPECT_NEAR(d.load_kpa(), 2.0, 1e-9);
  for (; k < 260; ++k)
    d.update(k * kPeriod, 1.0, kPeriod);
  EXPECT_FALSE(d.in_contact());
  EXPECT_NEAR(d.load_kpa(), 0.0, 1e-3);
}

}  // namespace
