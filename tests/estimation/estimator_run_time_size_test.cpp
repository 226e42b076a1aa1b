// The estimator at a run-time joint count (Eigen::Dynamic): on the shipped 4-joint files and a
// simulated log it gives what the fixed-count estimator a controller runs gives, with and without
// the per-joint networks, and allocates nothing per cycle; its parameter file loads for any count
// and a fixed-count program refuses another count; a 9-joint arm's nominal residual is the
// effort less RNEA and friction.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "support/allocation_counter.hpp"
#include "support/random_arm.hpp"
#include "support/temp_dir.hpp"
#include "tpf/dynamics/rnea.hpp"
#include "tpf/estimation/estimator_parameter_file.hpp"
#include "tpf/estimation/load_estimator.hpp"
#include "twin_fixture.hpp"

namespace tpf::test {
namespace {

/// Counts heap allocations (operator new and malloc) made while it is alive.
class HeapAllocationCounter {
 public:
  HeapAllocationCounter() : start_(heap_allocation_count()) {}
  std::size_t count() const { return heap_allocation_count() - start_; }

 private:
  std::size_t start_;
};

constexpr int kAnyCount = Eigen::Dynamic;
using AnySample = EstimatorSample<double, kAnyCount, kAnyCount>;

/// The shipped files of the 4-joint arm: identified model, pads, calibrated estimator, and the
/// per-joint networks when `with_networks`.
EstimatorFiles shipped_arm4_files(bool with_networks) {
  EstimatorFiles f;
  f.params = data_path("arm4.params.json");
  f.robot = data_path("arm4.robot.json");
  f.pads = data_path("arm4.pads.json");
  f.estimator = data_path("arm4.estimator.json");
  if (with_networks) f.weights = data_path("weights/arm4.tcn.json");
  return f;
}

/// |a − b| ≤ 1e-12 element by element, with where it failed.
template <typename A, typename B>
void expect_near_1e12(const A& a, const B& b, const char* what, std::size_t row) {
  ASSERT_EQ(a.size(), b.size()) << what << " row " << row;
  for (Eigen::Index i = 0; i < a.size(); ++i)
    ASSERT_NEAR(a[i], b[i], 1e-12) << what << "[" << i << "] row " << row;
}

/// Every output of the run-time-size estimator equals the fixed one's.
template <typename Fixed, typename Any>
void expect_same_output(const Fixed& f, const Any& a, std::size_t row) {
  ASSERT_EQ(f.status, a.status) << "row " << row;
  ASSERT_EQ(f.state, a.state) << "row " << row;
  ASSERT_EQ(f.contact, a.contact) << "row " << row;
  ASSERT_EQ(f.t, a.t) << "row " << row;
  expect_near_1e12(f.ddq, a.ddq, "ddq", row);
  expect_near_1e12(f.effort_rigid, a.effort_rigid, "effort_rigid", row);
  expect_near_1e12(f.effort_friction, a.effort_friction, "effort_friction", row);
  expect_near_1e12(f.residual, a.residual, "residual", row);
  expect_near_1e12(f.static_friction, a.static_friction, "static_friction", row);
  expect_near_1e12(f.compensation, a.compensation, "compensation", row);
  for (int e = 0; e < kTorqueEstimatorCount; ++e) {
    ASSERT_EQ(f.estimates[e].valid, a.estimates[e].valid) << "estimate " << e << " row " << row;
    expect_near_1e12(f.estimates[e].residual, a.estimates[e].residual, "estimate residual", row);
    expect_near_1e12(f.estimates[e].torque, a.estimates[e].torque, "estimate torque", row);
  }
  ASSERT_EQ(f.external.valid, a.external.valid) << "row " << row;
  expect_near_1e12(f.external.residual, a.external.residual, "external residual", row);
  expect_near_1e12(f.external.torque, a.external.torque, "external torque", row);
  ASSERT_EQ(f.wrench.pad, a.wrench.pad) << "row " << row;
  ASSERT_EQ(f.wrench.valid, a.wrench.valid) << "row " << row;
  ASSERT_EQ(f.wrench.observable_by_arm, a.wrench.observable_by_arm) << "row " << row;
  expect_near_1e12(f.wrench.force_world, a.wrench.force_world, "force_world", row);
  expect_near_1e12(f.wrench.force_contact, a.wrench.force_contact, "force_contact", row);
  expect_near_1e12(f.wrench.force_std_contact, a.wrench.force_std_contact, "force_std", row);
  expect_near_1e12(f.wrench.point_world, a.wrench.point_world, "point_world", row);
  if (std::isfinite(f.wrench.condition)) {
    ASSERT_NEAR(f.wrench.condition, a.wrench.condition, 1e-12 * f.wrench.condition) << row;
  }
  ASSERT_NEAR(f.wrench.inverse_condition, a.wrench.inverse_condition, 1e-12) << "row " << row;
}

/// Replays the static-contacts log through Estimator<double, 4, 11, Kind> and the estimators of
/// Eigen::Dynamic joints (with 11 and with Eigen::Dynamic pads) built from the same files, and
/// compares every output; the run-time-size updates allocate nothing.
template <typename Kind>
void expect_run_time_size_matches_fixed(const EstimatorFiles& files) {
  const auto fixed = load_estimator<kJoints, kPads, Kind>(files);
  const auto any = load_estimator<kAnyCount, kAnyCount, Kind>(files);
  const auto any_joints = load_estimator<kAnyCount, kPads, Kind>(files);
  ASSERT_EQ(any->joint_count(), kJoints);
  ASSERT_EQ(any->skin().count(), kPads);
  EXPECT_EQ(any->compensated_joints(), fixed->compensated_joints());
  const std::vector<ArmSample>& samples = static_contact_samples();
  std::vector<AnySample> any_samples;
  std::vector<EstimatorSample<double, kAnyCount, kPads>> any_joint_samples;
  for (const ArmSample& s : samples) {
    any_samples.push_back(any_count_sample<kAnyCount>(s));
    any_joint_samples.push_back(any_count_sample<kPads>(s));
  }
  std::size_t contacts = 0, wrenches = 0, allocations = 0;
  for (std::size_t r = 0; r < samples.size(); ++r) {
    const auto& f = fixed->update(samples[r]);
    const HeapAllocationCounter counter;
    const auto& a = any->update(any_samples[r]);
    const auto& b = any_joints->update(any_joint_samples[r]);
    allocations += counter.count();
    expect_same_output(f, a, r);
    expect_same_output(f, b, r);
    if (::testing::Test::HasFatalFailure()) return;
    contacts += f.contact ? 1 : 0;
    wrenches += f.wrench.pad >= 0 ? 1 : 0;
  }
  EXPECT_EQ(allocations, 0u) << "run-time-size updates allocated";
  // The comparison covered contacts and wrenches, not only free motion.
  EXPECT_GT(contacts, 100u);
  EXPECT_GT(wrenches, 100u);
}

TEST(EstimatorRunTimeSize, EigensHeapAllocationsAreCounted) {
  if (!mallocs_are_counted()) GTEST_SKIP() << "malloc is not counted on this platform";
  const HeapAllocationCounter counter;
  Eigen::VectorXd v = Eigen::VectorXd::Zero(9);
  v[0] = 1.0;
  EXPECT_GE(counter.count(), 1u) << v.transpose();
}

TEST(EstimatorRunTimeSize, MatchesTheFixedCountEstimatorWithoutNetworks) {
  expect_run_time_size_matches_fixed<NoCompensator>(shipped_arm4_files(false));
}

TEST(EstimatorRunTimeSize, MatchesTheFixedCountEstimatorWithPerJointNetworks) {
  const EstimatorFiles files = shipped_arm4_files(true);
  expect_run_time_size_matches_fixed<PerJointTcn<BFloat16Weights, 16>>(files);
  // The networks answer (the comparison is not of zeros).
  const auto any = load_estimator<kAnyCount, kAnyCount, PerJointTcn<BFloat16Weights, 16>>(files);
  const auto& out = any->update(any_count_sample<kAnyCount>(static_contact_samples()[0]));
  EXPECT_GT(out.compensation.cwiseAbs().maxCoeff(), 0.0);
}

TEST(EstimatorRunTimeSize, ASampleOfAnotherJointCountIsSkipped) {
  const auto any = load_estimator<kAnyCount, kAnyCount, NoCompensator>(shipped_arm4_files(false));
  AnySample s = any_count_sample<kAnyCount>(static_contact_samples()[0]);
  s.q = Eigen::VectorXd::Zero(3);
  EXPECT_EQ(any->update(s).status, kStatusNonFiniteInput);
}

/// Parameters of `n` joints with every per-joint vector distinct.
EstimatorParameters<double, kAnyCount> run_time_size_parameters(int n) {
  EstimatorParameters<double, kAnyCount> p;
  p.resize(n);
  for (int j = 0; j < n; ++j) {
    p.nominal_sigma[j] = 0.1 + 0.01 * j;
    p.fused_sigma[j] = 0.05 + 0.01 * j;
    p.static_dead_band[j] = 0.2 + 0.02 * j;
    p.compensator_speed_limit[j] = j % 2 == 0 ? 1.5 + j : std::numeric_limits<double>::infinity();
    p.compensator_acceleration_limit[j] = 20.0 + j;
  }
  p.torque_alarm_samples = 7;
  p.dead_band_factor = 2.0;
  return p;
}

TEST(EstimatorRunTimeSize, ParameterFileRoundTripsAtAnyJointCount) {
  const TempDir dir("estimator_run_time_size");
  const auto file = dir / "random9.estimator.json";
  const EstimatorParameters<double, kAnyCount> written = run_time_size_parameters(9);
  save_estimator_parameters(file, written, "test");
  const EstimatorParameters<double, kAnyCount> read = load_estimator_parameters(file);
  ASSERT_EQ(read.joint_count(), 9);
  EXPECT_EQ(read.nominal_sigma, written.nominal_sigma);
  EXPECT_EQ(read.fused_sigma, written.fused_sigma);
  EXPECT_EQ(read.static_dead_band, written.static_dead_band);
  EXPECT_EQ(read.compensator_speed_limit, written.compensator_speed_limit);
  EXPECT_EQ(read.compensator_acceleration_limit, written.compensator_acceleration_limit);
  EXPECT_EQ(read.torque_alarm_samples, 7);
  EXPECT_EQ(read.dead_band_factor, 2.0);
  EXPECT_EQ(load_estimator_parameters(file, 9).joint_count(), 9);

  // The 4-joint shipped file through the fixed-count wrapper and through the run-time one.
  const auto shipped = data_path("arm4.estimator.json");
  const auto fixed = load_estimator_parameters<kJoints>(shipped);
  const auto any = load_estimator_parameters<kAnyCount>(shipped);
  EXPECT_EQ(any.nominal_sigma, Eigen::VectorXd(fixed.nominal_sigma));
  EXPECT_EQ(joint_count_cast<kJoints>(any).static_dead_band, fixed.static_dead_band);

  // A fixed-count program refuses the 9-joint file, naming both counts.
  try {
    load_estimator_parameters<kJoints>(file);
    ADD_FAILURE() << "a 9-joint parameter file was loaded by a 4-joint program";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("9 joints"), std::string::npos) << message;
    EXPECT_NE(message.find("has 4"), std::string::npos) << message;
  }
  // So does the conversion of parameters already loaded.
  try {
    (void)joint_count_cast<kJoints>(read);
    ADD_FAILURE() << "9-joint parameters converted to 4 joints";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("9 joints"), std::string::npos) << message;
    EXPECT_NE(message.find("asks for 4"), std::string::npos) << message;
  }
  // And an estimator setup whose files are of another arm.
  EXPECT_THROW((load_estimator_setup<7>(shipped_arm4_files(false))), Error);
  const auto setup = load_estimator_setup<kAnyCount>(shipped_arm4_files(true));
  EXPECT_EQ(setup.nominal.model.joint_count(), kJoints);
  EXPECT_EQ(setup.weights.files.size(), std::size_t(kJoints));
}

TEST(EstimatorRunTimeSize, NineJointResidualIsEffortLessRneaAndFriction) {
  constexpr int n = 9;
  const Model<double, kAnyCount> model = random_arm(n, 5);
  StribeckParameters<double, kAnyCount> friction;
  friction.resize(n);
  for (int j = 0; j < n; ++j) {
    friction.coulomb[j] = 0.5 + 0.1 * j;
    friction.static_friction[j] = 0.8 + 0.1 * j;
    friction.viscous[j] = 0.2;
    friction.stribeck_velocity[j] = 0.05;
  }
  const NominalModel<double, kAnyCount> nominal = nominal_from_model(model, friction);
  Estimator<double, kAnyCount, 0> estimator(nominal, {}, run_time_size_parameters(n));
  ASSERT_EQ(estimator.joint_count(), n);
  Data<double, kAnyCount> data(nominal.model);
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  EstimatorSample<double, kAnyCount, 0> s;
  s.resize(n, 0);
  s.has_ddq = true;
  std::vector<EstimatorSample<double, kAnyCount, 0>> samples;
  for (int k = 0; k < 200; ++k) {
    s.t = 0.0025 * k;
    for (int j = 0; j < n; ++j) {
      s.q[j] = 1.5 * u(rng);
      s.dq[j] = k % 4 == 0 ? 0.0 : u(rng);  // some samples at rest: the tracker's baseline too
      s.ddq[j] = 3.0 * u(rng);
      s.effort[j] = 20.0 * u(rng);
    }
    samples.push_back(s);
  }
  std::vector<Eigen::VectorXd> residuals;
  residuals.reserve(samples.size());
  std::size_t allocations = 0;
  for (const auto& sample : samples) {
    const HeapAllocationCounter cycle;
    const auto& out = estimator.update(sample);
    allocations += cycle.count();
    residuals.push_back(out.residual);
    ASSERT_EQ(out.status & kStatusNonFiniteInput, 0u);
    ASSERT_EQ(out.external.valid, every_joint_mask(n));
  }
  EXPECT_EQ(allocations, 0u) << "a 9-joint estimator allocated in update()";
  for (std::size_t k = 0; k < samples.size(); ++k) {
    const auto& x = samples[k];
    const Eigen::VectorXd expected =
        x.effort - rnea(nominal.model, data, x.q, x.dq, x.ddq) - stribeck_friction(friction, x.dq);
    EXPECT_LT((residuals[k] - expected).norm(), 1e-8 * (1.0 + x.effort.norm())) << "sample " << k;
  }
}

TEST(EstimatorRunTimeSize, MoreJointsThanTheMasksHoldIsRefused) {
  const Model<double, kAnyCount> model = random_arm(33, 2);
  NominalModel<double, kAnyCount> nominal;
  nominal.model = model;
  nominal.resize(33);
  EstimatorParameters<double, kAnyCount> p;
  p.resize(33);
  EXPECT_THROW((Estimator<double, kAnyCount, 0>(nominal, {}, p)), Error);
  // Parameters of another joint count than the model are refused too.
  p.resize(9);
  nominal.model = random_arm(8, 2);
  nominal.resize(8);
  EXPECT_THROW((Estimator<double, kAnyCount, 0>(nominal, {}, p)), Error);
}

}  // namespace
}  // namespace tpf::test
