// Bad samples that are processed rather than skipped (a frozen sensor, positions out of range)
// must not live on: once good data is back the estimator returns to what a clean run gives
// (twin static-contacts log, simulated). The flags themselves: tests/reliability.
#include <gtest/gtest.h>

#include <functional>

#include "estimation/twin_fixture.hpp"

namespace tpf::test {
namespace {

constexpr std::size_t kBad = 900;  // mid push of the first contact

/// Runs the log with rows edited by `edit`; returns the outputs of every row.
std::vector<TwinEstimator::Output> run(const std::function<void(std::size_t, ArmSample&)>& edit) {
  auto est = std::make_unique<TwinEstimator>(twin_nominal(), twin_pads(), twin_parameters());
  std::vector<TwinEstimator::Output> out;
  for (std::size_t r = 0; r < kStaticContactRows; ++r) {
    ArmSample s = static_contact_samples()[r];
    edit(r, s);
    out.push_back(est->update(s));
  }
  return out;
}

/// From row `from` on, the run equals the clean one (the acceleration filter's memory of the bad
/// rows has decayed by then: e^(−ζω·0.5 s) < 1e-27).
void expect_back_on_clean_run(const std::vector<TwinEstimator::Output>& faulty, std::size_t from) {
  const auto clean = run([](std::size_t, ArmSample&) {});
  for (std::size_t r = from; r < kStaticContactRows; ++r) {
    ASSERT_LT((faulty[r].static_friction - clean[r].static_friction).cwiseAbs().maxCoeff(), 1e-6)
        << "row " << r;
    ASSERT_LT((faulty[r].external.torque - clean[r].external.torque).cwiseAbs().maxCoeff(), 1e-9)
        << "row " << r;
    ASSERT_EQ(faulty[r].state, clean[r].state) << "row " << r;
    ASSERT_EQ(faulty[r].wrench.pad, clean[r].wrench.pad) << "row " << r;
  }
}

TEST(BadSampleRecovery, AFrozenSensorLeavesNoTraceOnceLive) {
  const std::size_t end = kBad + 300;  // 0.75 s of one repeated reading
  const auto faulty = run([&](std::size_t r, ArmSample& s) {
    if (r > kBad && r < end) {
      const ArmSample& frozen = static_contact_samples()[kBad];
      s.q = frozen.q, s.dq = frozen.dq, s.effort = frozen.effort;
    }
  });
  EXPECT_TRUE(faulty[end - 1].status & kStatusFrozenInput);
  expect_back_on_clean_run(faulty, end + 200);
}

TEST(BadSampleRecovery, OutOfRangePositionsLeaveNoTrace) {
  const auto faulty = run([&](std::size_t r, ArmSample& s) {
    if (r >= kBad && r < kBad + 10) s.q[1] = arm().upper[1] + 1.0;
  });
  EXPECT_TRUE(faulty[kBad].status & kStatusPositionOutOfRange);
  expect_back_on_clean_run(faulty, kBad + 200);
}

}  // namespace
}  // namespace tpf::test
