// The loop's estimator hook without devices: cycle samples in, the core Estimator's outcome out.
// A failed motor read or stale pads are flagged in the status, never estimated from; the cycle
// allocates nothing; the estimator parameter file sets the dead bands; bad files are refused at
// start-up with the file named.
#include "arm/estimator_hook.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "support/allocation_counter.hpp"
#include "support/arm_fixture.hpp"
#include "tpf/common/error.hpp"
#include "tpf/estimation/estimator_parameter_file.hpp"
#include "tpf/estimation/estimator_status.hpp"
#include "tpf/estimation/proprioceptive_estimate.hpp"
#include "tpf/model/effort_unit.hpp"
#include "tpf/model/load_robot.hpp"

namespace tpf::arm {
namespace {

using test::data_path;

EstimatorFiles arm4_files() {
  EstimatorFiles f;
  f.params = data_path("arm4.params.json");
  f.robot = data_path("arm4.robot.json");
  f.pads = data_path("arm4.pads.json");
  f.estimator = data_path("arm4.estimator.json");  // calibrated on a SIMULATED log
  f.weights = data_path("weights/arm4.tcn.json");
  f.trace_capacity = 100;
  return f;
}

/// The arm at rest at q = (0, 0.3, −0.4, 0), pads unloaded (currents set by the caller).
/// The arm's model: its torque constants turn the estimator's N·m into the drives' mA.
const Model<double, 4>& arm4() {
  static const Model<double, 4> model = load_robot<double, 4>(data_path("arm4.robot.json"));
  return model;
}

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
  EXPECT_NE(hook.description().find("per-joint networks of 16 channels"), std::string::npos);
  CycleSample s = resting(0);
  hook.update(s);  // start-up of the filters and the networks
  // Feed the rigid-body effort the model predicts at rest as the measured current (mA).
  const JointVector<double, 4> current = current_from_torque(arm4(), hook.output().effort_rigid);
  for (int j = 0; j < 4; ++j)
    s.i[static_cast<std::size_t>(j)] = current[j];

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
  // The current went in through the robot file's K_t: at rest with the predicted current the
  // nominal residual is 0 (no friction is predicted at q̇ = 0), so the proprioceptive estimate
  // is 0.
  const auto& out = hook.output();
  EXPECT_LT(out.residual.cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_EQ(proprioceptive_estimate(out, hook.parameters()).torque.cwiseAbs().maxCoeff(), 0.0);
}

/// A file in the temporary folder, removed at the end of the test.
struct TempFile {
  explicit TempFile(const std::string& name)
      : path(std::filesystem::temp_directory_path() /
             (name + "." + std::to_string(::getpid()) + ".json")) {}
  ~TempFile() { std::filesystem::remove(path); }
  std::filesystem::path path;
};

/// The proprioceptive estimate (after its dead band, N·m) of the arm at rest whose currents exceed
/// the model's by `offset_ma` on every joint, from a hook with estimator parameter file `file`.
JointVector<double, 4> proprioceptive_at_rest(const std::string& file, double offset_ma) {
  EstimatorFiles f = arm4_files();
  f.estimator = file;
  EstimatorHook hook(f);
  EXPECT_NE(hook.description().find("parameters " + file), std::string::npos);
  CycleSample s = resting(0);
  hook.update(s);
  const JointVector<double, 4> current = current_from_torque(arm4(), hook.output().effort_rigid);
  for (int j = 0; j < 4; ++j)
    s.i[static_cast<std::size_t>(j)] = current[j] + offset_ma;
  for (std::uint64_t n = 1; n < 40; ++n) {
    s.cycle = n;
    s.t = 0.0025 * static_cast<double>(n);
    hook.update(s);
  }
  EXPECT_EQ(hook.output().status, kStatusOk);
  return proprioceptive_estimate(hook.output(), hook.parameters()).residual;
}

TEST(EstimatorHook, TheEstimatorFileSetsTheDeadBands) {
  // The shipped file's proprioceptive dead band is 1.5·σ_nominal per joint (N·m): a 300 mA
  // residual, K_t·0.3 N·m, passes it by that less 1.5·σ_j where σ_j < 200 mA and not elsewhere.
  const auto shipped = load_estimator_parameters<4>(data_path("arm4.estimator.json"));
  const JointVector<double, 4> band = shipped.dead_band_factor * shipped.nominal_sigma;
  const JointVector<double, 4> push =
      torque_from_current(arm4(), JointVector<double, 4>::Constant(300.0).eval());
  const JointVector<double, 4> r = proprioceptive_at_rest(data_path("arm4.estimator.json"), 300.0);
  for (int j = 0; j < 4; ++j)
    EXPECT_NEAR(r[j], std::max(push[j] - band[j], 0.0), 1e-6) << "joint " << j + 1;
  EXPECT_GT(r.maxCoeff(), 0.0);  // the data file has a joint with σ < 200 mA

  // The same file with every σ_nominal at 1000 mA: no joint leaves its band.
  TempFile wide("tpf_hook_wide_band");
  auto p = shipped;
  p.nominal_sigma = torque_from_current(arm4(), JointVector<double, 4>::Constant(1000.0).eval());
  save_estimator_parameters<4>(wide.path, p, "test: wide dead bands");
  EXPECT_EQ(proprioceptive_at_rest(wide.path.string(), 300.0).cwiseAbs().maxCoeff(), 0.0);
}

TEST(EstimatorHook, RefusesBadFilesNamingThem) {
  EstimatorFiles f = arm4_files();
  f.pads = data_path("no-such-pads.json");
  try {
    EstimatorHook hook(f);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no-such-pads.json"), std::string::npos) << e.what();
  }
  f = arm4_files();
  f.weights = data_path("weights/none-here.json");
  EXPECT_THROW(EstimatorHook{f}, Error);
  // An estimator parameter file with a field missing: the file and the field are named.
  TempFile bad("tpf_hook_bad_estimator");
  std::ifstream in(data_path("arm4.estimator.json"));
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto at = text.find("\"torque_alarm_samples\"");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, std::string("\"torque_alarm_samples\"").size(), "\"torque_alarm\"");
  std::ofstream(bad.path) << text;
  f = arm4_files();
  f.estimator = bad.path.string();
  try {
    EstimatorHook hook(f);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(bad.path.string() + ": torque_alarm_samples: missing"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace tpf::arm
