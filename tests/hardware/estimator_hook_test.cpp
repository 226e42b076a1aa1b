// The loop's estimator hook without devices: cycle samples in, the core Estimator's outcome out.
// A failed motor read or stale pads are flagged in the status, never estimated from; the cycle
// allocates nothing; bad files are refused at start-up with the file named.
#include "arm/estimator_hook.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <string>

#include "offline/sim/scenario.hpp"
#include "offline/sim/simulate.hpp"
#include "support/allocation_counter.hpp"
#include "tpf/common/error.hpp"
#include "tpf/estimation/estimator_status.hpp"

namespace tpf::arm {
namespace {

std::string data(const std::string& name) {
  return std::string(TPF_TEST_DATA_DIR) + "/" + name;
}

EstimatorFiles arm4_files() {
  EstimatorFiles f;
  f.params = data("arm4.params.json");
  f.robot = data("arm4.robot.json");
  f.pads = data("arm4.pads.json");
  f.weights = data("weights/arm4.tcn.json");
  f.trace_capacity = 100;
  return f;
}

/// The arm at rest at q = (0, 0.3, −0.4, 0), pads unloaded (currents set by the caller).
CycleSample resting(std::uint64_t n) {
  CycleSample s;
  s.cycle = n;
  s.t = 0.0025 * static_cast<double>(n);
  s.joints = 4;
  s.motors_valid = true;
  s.q = {0.0, 0.3, -0.4, 0.0};
  s.pads = 11;
  s.pads_valid = true;
  return s;
}

TEST(EstimatorHook, FlagsFaultyCyclesAndDoesNotAllocate) {
  EstimatorHook hook(arm4_files());
  EXPECT_NE(hook.description().find("one friction network per joint"), std::string::npos);
  CycleSample s = resting(0);
  hook.update(s);  // start-up of the filters and the networks
  // Feed the rigid-body effort the model predicts at rest as the measured current.
  for (int j = 0; j < 4; ++j)
    s.i[static_cast<std::size_t>(j)] = hook.output().effort_rigid[j];

  test::AllocationCounter allocations;
  for (std::uint64_t n = 1; n < 60; ++n) {
    CycleSample c = s;
    c.cycle = n;
    c.t = 0.0025 * static_cast<double>(n);
    if (n == 20) c.motors_valid = false;          // a failed motor read (values stale)
    if (n >= 30 && n < 35) c.pads_valid = false;  // pads unplugged
    hook.update(c);
    const std::uint32_t status = hook.output().status;
    EXPECT_EQ(status == kStatusNonFiniteInput, n == 20) << n;
    EXPECT_EQ((status & kStatusTimeGap) != 0, n == 21) << n;  // 5 ms since the last one
    EXPECT_EQ((status & kStatusPadDataInvalid) != 0, n >= 30 && n < 35) << n;
  }
  EXPECT_EQ(allocations.count(), 0u);

  const EstimatorStatistics& st = hook.statistics();
  EXPECT_EQ(st.updates, 60u);
  EXPECT_EQ(st.status_bit[0], 1u);  // non-finite input
  EXPECT_EQ(st.status_bit[2], 1u);  // time gap
  EXPECT_EQ(st.status_bit[4], 5u);  // pad data invalid
  EXPECT_EQ(st.contact_cycles, 0u);
  EXPECT_EQ(st.non_finite_estimates, 0u);
  ASSERT_EQ(hook.trace().size(), 60u);
  EXPECT_EQ(hook.trace()[20].status, kStatusNonFiniteInput);
  EXPECT_DOUBLE_EQ(hook.trace()[59].t, 59 * 0.0025);
  // The current went in as the effort in mA: at rest with the predicted current the nominal
  // residual is 0 (no friction is predicted at q̇ = 0), so the proprioceptive estimate is 0.
  const auto& out = hook.output();
  EXPECT_LT(out.residual.cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_EQ(out.estimate(TorqueEstimator::Proprioceptive).torque.cwiseAbs().maxCoeff(), 0.0);
}

TEST(EstimatorHook, ReadsItsDeadBandsOffACalibrationLog) {
  // A contact-free twin log (simulated, excitation: rests and moves on every joint).
  const std::string log = std::string(std::getenv("TMPDIR") ? std::getenv("TMPDIR") : "/tmp") +
                          "/tpf_hook_calibration_" + std::to_string(::getpid()) + ".csv";
  offline::simulate_to_file(offline::load_scenario(data("scenarios/excitation.json")), 11, 20.0,
                            log);
  EstimatorFiles f = arm4_files();
  f.calibration_log = log;
  EstimatorHook hook(f);
  EXPECT_NE(hook.description().find("dead bands from " + log), std::string::npos);
  std::remove(log.c_str());
}

TEST(EstimatorHook, RefusesBadFilesNamingThem) {
  EstimatorFiles f = arm4_files();
  f.pads = data("no-such-pads.json");
  try {
    EstimatorHook hook(f);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no-such-pads.json"), std::string::npos) << e.what();
  }
  f = arm4_files();
  f.weights = data("weights/none-here.json");
  EXPECT_THROW(EstimatorHook{f}, Error);
}

}  // namespace
}  // namespace tpf::arm
