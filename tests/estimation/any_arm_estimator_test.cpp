// One estimator type for any arm: load_estimator<N, P, Compensator> builds it from the files the
// offline tools write, for a 1-joint bench, the 4-joint arm (with and without its 11 pads) and the
// 7-joint Kinova Gen3 (no skin). Checked against ground truth: with effort = the nominal model's
// prediction − K·τ_ext, every joint's external torque is τ_ext exactly (no dead band before
// calibration), and the per-cycle update allocates nothing.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "support/allocation_counter.hpp"
#include "support/arm_fixture.hpp"
#include "tpf/estimation/estimator_parameter_file.hpp"
#include "tpf/estimation/load_estimator.hpp"

namespace tpf {
namespace {

namespace fs = std::filesystem;

/// A folder of files for one test, removed afterwards.
struct TempFolder {
  fs::path path = fs::temp_directory_path() / ("tpf_any_arm_" + std::to_string(::getpid()));
  TempFolder() { fs::create_directories(path); }
  ~TempFolder() { fs::remove_all(path); }
};

/// A 1-joint bench: a 0.5 kg rod on a horizontal axis, geared 100:1.
fs::path write_bench(const fs::path& dir) {
  std::ofstream(dir / "bench1.urdf") << R"(<robot name="bench1">
  <link name="base"/>
  <joint name="axis" type="revolute">
    <parent link="base"/><child link="rod"/><origin xyz="0 0 0.5"/><axis xyz="0 1 0"/>
    <limit lower="-3" upper="3" effort="20" velocity="3"/>
  </joint>
  <link name="rod"><inertial><origin xyz="0.15 0 0"/><mass value="0.5"/>
    <inertia ixx="1e-4" iyy="4e-3" izz="4e-3" ixy="0" ixz="0" iyz="0"/></inertial></link>
</robot>)";
  std::ofstream(dir / "bench1.robot.json") << R"({"format": "tpf-robot", "version": 1,
  "name": "bench1", "urdf": "bench1.urdf",
  "joints": [{"name": "axis", "gear_ratio": 100, "rotor_inertia": 5e-6, "torque_constant": 2.0,
              "current_limit": 5000}], "units": {}})";
  return dir / "bench1.robot.json";
}

/// The nominal model (the robot's rigid body, a Stribeck curve) and default estimator parameters
/// of an N-joint robot written as files, as `tpf identify` and `tpf calibrate` would.
template <int N>
EstimatorFiles write_model_files(const fs::path& dir, const std::string& robot) {
  const Model<double, N> model = load_robot<double, N>(robot);
  StribeckParameters<double, N> friction;
  friction.coulomb.setConstant(0.8);
  friction.static_friction.setConstant(1.1);
  friction.viscous.setConstant(0.3);
  friction.stribeck_velocity.setConstant(0.05);
  const NominalModel<double, N> nominal = nominal_from_model<N>(model, friction);
  EstimatorFiles files;
  files.params = (dir / "model.params.json").string();
  files.robot = robot;
  files.estimator = (dir / "model.estimator.json").string();
  save_nominal_model<N>(files.params, nominal, "test");
  save_estimator_parameters<N>(files.estimator, EstimatorParameters<double, N>{}, "test");
  return files;
}

/// Runs the estimator over 2 s of every joint turning at 0.3 rad/s (always moving, so the
/// fused estimate answers) with a known external torque on every joint; checks τ̂_ext = τ_ext and
/// that the updates allocate nothing.
template <int N, int P, typename Kind>
void expect_exact_external_torque(const EstimatorFiles& files) {
  const auto estimator = load_estimator<N, P, Kind>(files);
  const NominalModel<double, N>& nominal = estimator->nominal();
  Data<double, N> data(nominal.model);
  std::vector<EstimatorSample<double, N, P>> samples(800);
  std::vector<JointVector<double, N>> truth(samples.size());
  for (std::size_t k = 0; k < samples.size(); ++k) {
    EstimatorSample<double, N, P>& s = samples[k];
    s.t = 0.0025 * static_cast<double>(k);
    s.dq.setConstant(0.3);
    s.q = JointVector<double, N>::Constant(0.1) + s.t * s.dq;
    JointVector<double, N> rigid, friction;
    predict_effort(nominal, data, s.q, s.dq, JointVector<double, N>::Zero().eval(), rigid,
                   friction);
    for (int j = 0; j < N; ++j)
      truth[k][j] = 0.5 * (j + 1) * std::sin(2.0 * s.t + j);  // N·m
    s.effort = rigid + friction - truth[k];
  }
  test::AllocationCounter counter;
  double worst = 0.0;
  bool contact = false;
  for (std::size_t k = 0; k < samples.size(); ++k) {
    const auto& out = estimator->update(samples[k]);
    worst = std::max(worst, (out.external.torque - truth[k]).cwiseAbs().maxCoeff());
    contact = out.contact;
  }
  EXPECT_EQ(counter.count(), 0u) << N << " joints, " << P << " pads";
  EXPECT_TRUE(contact) << "a torque of " << truth.back().transpose() << " N·m is a contact";
  EXPECT_LT(worst, 1e-6) << N << " joints, " << P << " pads";
}

TEST(AnyArmEstimator, OneJointBenchWithoutSkin) {
  TempFolder dir;
  const EstimatorFiles files = write_model_files<1>(dir.path, write_bench(dir.path).string());
  expect_exact_external_torque<1, 0, NoCompensator>(files);
}

TEST(AnyArmEstimator, FourJointArmWithAndWithoutItsPads) {
  TempFolder dir;
  EstimatorFiles files = write_model_files<4>(dir.path, test::data_path("arm4.robot.json"));
  expect_exact_external_torque<4, 0, NoCompensator>(files);
  files.pads = test::data_path("arm4.pads.json");
  expect_exact_external_torque<4, 11, NoCompensator>(files);
  // The shipped per-joint networks load into their named type; a wrong kind is refused.
  files.weights = test::data_path("weights/arm4.tcn.json");
  EXPECT_NO_THROW((load_estimator<4, 11, PerJointTcn<BFloat16Weights, 16>>(files)));
  try {
    load_estimator<4, 11, PerJointTcn<float, 32>>(files);
    ADD_FAILURE() << "16-channel weights loaded into a 32-channel compensator";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("per-joint networks of 16 channels"), std::string::npos)
        << e.what();
  }
  // An estimator built for no skin refuses a pad layout, naming the count.
  files.weights.clear();
  EXPECT_THROW((load_estimator<4, 0, NoCompensator>(files)), Error);
}

TEST(AnyArmEstimator, SevenJointKinovaWithoutSkin) {
  TempFolder dir;
  const EstimatorFiles files =
      write_model_files<7>(dir.path, test::data_path("real/kinova-gen3/gen3.robot.json"));
  expect_exact_external_torque<7, 0, NoCompensator>(files);
}

TEST(AnyArmEstimator, AJointCountOtherThanTheRobotsIsRefused) {
  TempFolder dir;
  const EstimatorFiles files = write_model_files<4>(dir.path, test::data_path("arm4.robot.json"));
  EXPECT_THROW((load_estimator<7, 0, NoCompensator>(files)), Error);
}

}  // namespace
}  // namespace tpf
