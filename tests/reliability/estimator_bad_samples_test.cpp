// The run-time Estimator under bad samples (all data simulated by the twin): NaN and infinity in
// every field, time going backwards, a long gap, out-of-range positions, a frozen sensor and a pad
// stuck high. Each is flagged in the status, none leaks into later estimates, and the estimator
// is back to what a clean run gives once good data returns.
#include <gtest/gtest.h>

#include <functional>
#include <limits>

#include "estimation/twin_fixture.hpp"

namespace tpf::test {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr std::size_t kRows = 2400;  // 6 s at 400 Hz
constexpr std::size_t kBad = 900;    // the row the faults hit (mid push of the first contact)

const std::vector<ArmSample>& samples() {
  static const std::vector<ArmSample> s = samples_from_log(twin_log("static-contacts", 5, 7));
  return s;
}

std::unique_ptr<TwinEstimator> make_estimator() {
  return std::make_unique<TwinEstimator>(twin_nominal(), twin_pads(), twin_parameters());
}

bool finite(const TwinEstimator::Output& o) {
  return o.residual.allFinite() && o.external.torque.allFinite() && o.compensation.allFinite() &&
         o.static_friction.allFinite() && o.ddq.allFinite() && o.wrench.force_world.allFinite();
}

/// Runs rows [0, rows) through `est`, row r replaced by edit(r, sample) (which may return false
/// to drop the row); calls check(r, output) after each fed row.
void run(TwinEstimator& est, const std::function<bool(std::size_t, ArmSample&)>& edit,
         const std::function<void(std::size_t, const TwinEstimator::Output&)>& check = {},
         std::size_t rows = kRows) {
  for (std::size_t r = 0; r < rows; ++r) {
    ArmSample s = samples()[r];
    if (!edit(r, s)) continue;
    const auto& out = est.update(s);
    if (check) check(r, out);
  }
}

/// Outputs of a clean run of `rows` rows without row `skipped` (or of all rows).
TwinEstimator::Output clean_output(std::size_t skipped = kRows, std::size_t rows = kRows) {
  auto est = make_estimator();
  run(
      *est, [&](std::size_t r, ArmSample&) { return r != skipped; }, {}, rows);
  return est->output();
}

/// The field-by-field test stops this long after the bad row (0.5 s is past every filter's
/// memory of one sample; it keeps 39 runs cheap under the sanitizers).
constexpr std::size_t kShortRows = kBad + 200;

void expect_same(const TwinEstimator::Output& a, const TwinEstimator::Output& b) {
  EXPECT_EQ(a.t, b.t);
  EXPECT_EQ(a.residual, b.residual);
  EXPECT_EQ(a.external.torque, b.external.torque);
  EXPECT_EQ(a.static_friction, b.static_friction);
  EXPECT_EQ(a.state, b.state);
  EXPECT_EQ(a.status, b.status);
}

TEST(EstimatorBadSamples, TheCleanTwinLogRaisesNoFlag) {
  ASSERT_GE(samples().size(), kRows);
  auto est = make_estimator();
  run(
      *est, [](std::size_t, ArmSample&) { return true; },
      [](std::size_t r, const TwinEstimator::Output& o) {
        // Gaps are the twin's deliberately dropped cycles; pads in contact may be unobservable.
        EXPECT_EQ(o.status & ~(kStatusTimeGap | kStatusWrenchUnobservable), 0u) << "row " << r;
        ASSERT_TRUE(finite(o)) << "row " << r;
      });
}

// Every field of t, q, q̇ and the effort, set to NaN, +inf and −inf in one sample.
TEST(EstimatorBadSamples, NonFiniteValueInAnyFieldIsFlaggedSkippedAndForgotten) {
  const auto reference = clean_output(kBad, kShortRows);
  std::vector<std::pair<std::string, std::function<double&(ArmSample&)>>> fields = {
      {"t", [](ArmSample& s) -> double& { return s.t; }}};
  for (int j = 0; j < kJoints; ++j) {
    fields.push_back({std::string("q").append(std::to_string(j + 1)),
                      [j](ArmSample& s) -> double& { return s.q[j]; }});
    fields.push_back({std::string("dq").append(std::to_string(j + 1)),
                      [j](ArmSample& s) -> double& { return s.dq[j]; }});
    fields.push_back({std::string("effort").append(std::to_string(j + 1)),
                      [j](ArmSample& s) -> double& { return s.effort[j]; }});
  }
  for (const auto& entry : fields) {
    const std::string& name = entry.first;
    const auto& field = entry.second;  // (a lambda cannot capture a structured binding in C++20)
    for (const double bad : {kNaN, kInf, -kInf}) {
      SCOPED_TRACE(name + " = " + std::to_string(bad));
      auto est = make_estimator();
      TwinEstimator::Output before;
      run(
          *est,
          [&](std::size_t r, ArmSample& s) {
            if (r == kBad) before = est->output(), field(s) = bad;
            return true;
          },
          [&](std::size_t r, const TwinEstimator::Output& o) {
            if (r != kBad) return;
            EXPECT_EQ(o.status, kStatusNonFiniteInput);
            EXPECT_EQ(o.t, before.t);
            EXPECT_EQ(o.external.torque, before.external.torque);
          },
          kShortRows);
      expect_same(est->output(), reference);  // as if the bad row had never come
    }
  }
}

TEST(EstimatorBadSamples, TimeGoingBackwardsIsFlaggedAndSkipped) {
  const auto reference = clean_output(kBad);
  auto est = make_estimator();
  run(
      *est,
      [](std::size_t r, ArmSample& s) {
        if (r == kBad) s.t -= 0.5;
        return true;
      },
      [](std::size_t r, const TwinEstimator::Output& o) {
        if (r == kBad) {
          EXPECT_EQ(o.status, kStatusStaleTime);
        }
      });
  expect_same(est->output(), reference);
}

// A bad pressure or q̈ does not skip the sample: only that input is replaced (the pad holds its
// state, q̈ falls back to the filtered derivative), and the run is back on the clean one.
TEST(EstimatorBadSamples, BadPadPressureAndAccelerationAreFlaggedAndReplaced) {
  const auto reference = clean_output();
  for (const double bad : {kNaN, kInf, -kInf}) {
    auto est = make_estimator();
    run(
        *est,
        [&](std::size_t r, ArmSample& s) {
          if (r == kBad) s.pressure[8] = bad, s.pressure[0] = bad;
          if (r == kBad + 1) s.has_ddq = true, s.ddq.setConstant(bad);
          return true;
        },
        [&](std::size_t r, const TwinEstimator::Output& o) {
          if (r == kBad) {
            EXPECT_TRUE(o.status & kStatusPadDataInvalid);
          }
          if (r == kBad + 1) {
            EXPECT_TRUE(o.status & kStatusAccelerationEstimated);
          }
          if (r > kBad + 1) {
            EXPECT_FALSE(o.status & (kStatusPadDataInvalid | kStatusAccelerationEstimated));
          }
          ASSERT_TRUE(finite(o)) << "row " << r;
        });
    EXPECT_NEAR((est->output().external.torque - reference.external.torque).norm(), 0.0, 1e-6);
    EXPECT_EQ(est->output().state, reference.state);
  }
}

TEST(EstimatorBadSamples, LongGapIsFlaggedOnceAndFiltersStayFinite) {
  // The twin drops a cycle now and then on purpose: those rows are flagged in any run.
  const auto p = twin_parameters();
  const auto natural_gap = [&](std::size_t r) {
    return samples()[r].t - samples()[r - 1].t > p.max_gap_factor * p.sample_period_s;
  };
  auto est = make_estimator();
  const std::size_t first_after = kBad + 800;  // 2 s of samples lost
  run(
      *est, [&](std::size_t r, ArmSample&) { return r < kBad || r >= first_after; },
      [&](std::size_t r, const TwinEstimator::Output& o) {
        if (r >= first_after) {
          EXPECT_EQ(static_cast<bool>(o.status & kStatusTimeGap),
                    r == first_after || natural_gap(r))
              << "row " << r;
        }
        ASSERT_TRUE(finite(o)) << "row " << r;
      });
}

TEST(EstimatorBadSamples, OutOfRangePositionIsFlaggedOnlyWhileOut) {
  auto est = make_estimator();
  run(
      *est,
      [](std::size_t r, ArmSample& s) {
        if (r >= kBad && r < kBad + 10) s.q[1] = arm().upper[1] + 1.0;
        return true;
      },
      [](std::size_t r, const TwinEstimator::Output& o) {
        EXPECT_EQ(static_cast<bool>(o.status & kStatusPositionOutOfRange),
                  r >= kBad && r < kBad + 10)
            << "row " << r;
        ASSERT_TRUE(finite(o)) << "row " << r;
      });
}

// The drive keeps answering with one stale reading: flagged after frozen_limit_samples repeats,
// cleared by the first live sample.
TEST(EstimatorBadSamples, FrozenSensorIsFlaggedAfterTheLimitAndClearsWhenLive) {
  const int limit = twin_parameters().frozen_limit_samples;
  ASSERT_GT(limit, 0);
  const std::size_t end = kBad + static_cast<std::size_t>(limit) + 100;
  auto est = make_estimator();
  run(
      *est,
      [&](std::size_t r, ArmSample& s) {
        if (r > kBad && r < end) {
          const ArmSample& frozen = samples()[kBad];
          s.q = frozen.q, s.dq = frozen.dq, s.effort = frozen.effort;
        }
        return true;
      },
      [&](std::size_t r, const TwinEstimator::Output& o) {
        const bool frozen = r > kBad + static_cast<std::size_t>(limit) && r < end;
        EXPECT_EQ(static_cast<bool>(o.status & kStatusFrozenInput), frozen) << "row " << r;
        ASSERT_TRUE(finite(o)) << "row " << r;
      });
}

// A pad reads 30 kPa whatever happens (a blocked tube): flagged after the limit; once it reads
// live again the flag clears and its contact flag follows the clean run. (That the phantom
// contact does not reach later estimates: tests/estimation/stuck_pad_test.cpp.)
TEST(EstimatorBadSamples, PadStuckHighIsFlaggedAndContactRecovers) {
  const int limit = twin_parameters().stuck_pad_limit_samples;
  const std::size_t end = kBad + static_cast<std::size_t>(limit) + 100;
  auto clean = make_estimator();
  auto est = make_estimator();
  run(
      *est,
      [&](std::size_t r, ArmSample& s) {
        if (r >= kBad && r < end) s.pressure[5] = 30.0;
        clean->update(samples()[r]);
        return true;
      },
      [&](std::size_t r, const TwinEstimator::Output& o) {
        const bool stuck = r > kBad + static_cast<std::size_t>(limit) && r < end;
        EXPECT_EQ(static_cast<bool>(o.status & kStatusPadStuck), stuck) << "row " << r;
        if (r > end + 400) {
          EXPECT_EQ(est->skin().in_contact(5), clean->skin().in_contact(5)) << r;
        }
        ASSERT_TRUE(finite(o)) << "row " << r;
      });
}

}  // namespace
}  // namespace tpf::test
