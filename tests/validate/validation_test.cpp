// tpf validate's scoring on logs made by a small analytic generator (not the twin): a 1-joint
// arm with a vertical axis (no gravity torque) and no acceleration, so the nominal model predicts
// exactly its friction, and every RMSE is known in closed form.
#include "offline/validate/validation.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "offline/log/log_writer.hpp"
#include "offline/log/read_logs.hpp"
#include "tpf/model/load_robot.hpp"

namespace tpf::offline {
namespace {

constexpr double kKt = 2.0;            // N·m/A → 500 mA per N·m
constexpr double kCoulomb = 150.0;     // mA
constexpr double kViscous = 100.0;     // mA/(rad/s)
constexpr double kSpeed = 0.5;         // rad/s when moving
constexpr double kEffortNoise = 30;    // mA, ± on alternate samples
constexpr double kSensorNoise = 0.05;  // N·m, + on two samples, − on the next two
constexpr double kMakerOffset = 0.2;   // N·m

class TempFolder {
 public:
  TempFolder()
      : path_(std::filesystem::temp_directory_path() /
              ("tpf_validate_test_" + std::to_string(::getpid()))) {
    std::filesystem::create_directories(path_);
  }
  ~TempFolder() { std::filesystem::remove_all(path_); }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

void write(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path) << text;
}

std::filesystem::path write_robot(const TempFolder& dir) {
  write(dir / "turntable.urdf", R"(<?xml version="1.0"?>
<robot name="turntable">
  <link name="base"/>
  <link name="table">
    <inertial><origin xyz="0.1 0 0"/><mass value="2"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.03"/></inertial>
  </link>
  <joint name="joint1" type="revolute">
    <parent link="base"/><child link="table"/><axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" velocity="3" effort="50"/>
  </joint>
</robot>)");
  write(dir / "turntable.robot.json", R"({"format": "tpf-robot", "version": 1,
  "name": "turntable", "urdf": "turntable.urdf", "gravity": [0, 0, -9.81],
  "joints": [{"name": "joint1", "motor": "test", "gear_ratio": 100, "rotor_inertia": 1e-5,
              "torque_constant": 2.0, "current_limit": 10000}]})");
  return dir / "turntable.robot.json";
}

/// 4 s at 100 Hz: 1 s at rest, then kSpeed; i = friction + (±kEffortNoise); tau_sensor =
/// K_t·i − friction − (±kSensorNoise) (or 0 when `flat_sensor`); tau_maker = tau_sensor + offset.
Log turntable_log(bool flat_sensor) {
  Log log;
  log.meta.set("rate_hz", "100");
  log.columns = {"t", "q1", "dq1", "ddq1", "i1", "tau_sensor1", "tau_maker1"};
  log.values.resize(400, 7);
  for (int k = 0; k < 400; ++k) {
    const double t = k / 100.0;
    const bool moving = k >= 100;
    const double dq = moving ? kSpeed : 0.0;
    const double friction = moving ? kCoulomb + kViscous * kSpeed : 0.0;  // mA
    const double i = friction + (k % 2 == 0 ? kEffortNoise : -kEffortNoise);
    const double sensor_error = k % 4 < 2 ? kSensorNoise : -kSensorNoise;
    const double sensor = flat_sensor ? 0.0 : kKt * i / 1000 - friction / 500 - sensor_error;
    log.values.row(k) << t, moving ? kSpeed * (t - 1.0) : 0.0, dq, 0.0, i, sensor,
        sensor + kMakerOffset;
  }
  return log;
}

TEST(Validate, ScoresAHeldOutLogExactly) {
  TempFolder dir;
  const auto robot = write_robot(dir);
  const auto model = load_robot<double, 1>(robot);
  StribeckParameters<double, 1> friction;
  // The generator's friction is in mA; the model's in N·m (K_t = 2 N·m/A: 1 mA = 1/500 N·m).
  friction.coulomb << kCoulomb / 500;
  friction.static_friction << kCoulomb / 500;
  friction.stribeck_velocity << 0.1;
  friction.stribeck_exponent << 2.0;
  friction.viscous << kViscous / 500;
  const auto truth = nominal_from_model<1>(model, friction);
  save_nominal_model<1>(dir / "p.json", truth);
  const NominalModelX nominal = load_nominal_model(dir / "p.json", robot, 1);
  write_log(dir / "a.csv", turntable_log(false));
  write_log(dir / "b.csv.gz", turntable_log(true));
  const Log log = read_logs(std::vector<std::filesystem::path>{dir / "a.csv", dir / "b.csv.gz"});
  const JointSamples samples = extract_joint_samples(log, model.torque_constant);
  std::vector<std::string> notes;
  const Validation v = score_estimates(log, samples, {nominal_estimate(nominal, samples, notes)});

  // Effort: ±30 mA on every sample, whatever the regime, in both files.
  const RegimeStats& s = v.effort[0][0];
  EXPECT_EQ(s.valid.count, 800u);
  for (const Regime r : {Regime::Static, Regime::StaticToKinetic, Regime::Moving}) {
    EXPECT_GT(s[r].count, 0u);
    EXPECT_NEAR(s[r].rmse, kEffortNoise, 1e-9) << regime_name(r);
  }
  EXPECT_NEAR(v.effort_by_file[0][1][0].rmse, kEffortNoise, 1e-9);

  // Sensor: only the file where it varies (400 samples). The model's friction is exactly the
  // generator's, so K_t·i − d − τ_sensor is the ±0.05 N·m sensor error; K_t only keeps the
  // friction: √((100·0.05² + 300·(0.4² + 0.05²)) / 400) = √0.1225 = 0.35 N·m.
  ASSERT_EQ(v.sensor.size(), 1u);
  EXPECT_EQ(v.sensor[0].samples, 400u);
  const SensorScore& sensor = v.sensor[0];
  EXPECT_NEAR(sensor.estimates[0].valid.rmse, kSensorNoise, 1e-9);
  EXPECT_NEAR(sensor.kt_only.valid.rmse, 0.35, 1e-9);
  EXPECT_NEAR(sensor.maker.valid.rmse, kMakerOffset, 1e-9);
  // Per regime: at rest K_t only is the sensor error alone, moving it carries 0.4 N·m friction.
  EXPECT_NEAR(sensor.kt_only[Regime::Static].rmse, kSensorNoise, 1e-9);
  double sum = 0.0;
  int moving = 0;
  for (int k = 0; k < 400; ++k)
    if (samples.regimes[0][static_cast<std::size_t>(k)] == Regime::Moving) {
      sum += std::pow(0.4 + (k % 4 < 2 ? kSensorNoise : -kSensorNoise), 2);
      ++moving;
    }
  EXPECT_GT(moving, 250);
  EXPECT_NEAR(sensor.kt_only[Regime::Moving].rmse, std::sqrt(sum / moving), 1e-9);
  EXPECT_NEAR(sensor.estimates[0][Regime::Moving].rmse, kSensorNoise, 1e-9);
  ASSERT_EQ(sensor.by_file.size(), 2u);
  EXPECT_NEAR(sensor.by_file[0][1], 0.35, 1e-9);
  EXPECT_NEAR(sensor.by_file[0][2], kSensorNoise, 1e-9);
  EXPECT_TRUE(std::isnan(sensor.by_file[1][1]));  // flat sensor: not scored
  ASSERT_EQ(v.sensor_notes.size(), 1u);
  EXPECT_NE(v.sensor_notes[0].find("b.csv.gz: flat"), std::string::npos) << v.sensor_notes[0];
  EXPECT_NE(validation_text(v).find("0.350"), std::string::npos) << validation_text(v);
}

// A regime without held-out samples prints "-" and says why, never "nan": here every sample is
// moving (static and static-to-kinetic are empty), the effort residual 0.2 everywhere.
TEST(ValidationText, RegimeWithoutSamplesIsMarkedNotNaN) {
  const Eigen::VectorXd residual = Eigen::VectorXd::Constant(6, 0.2);
  const std::vector<Regime> labels(6, Regime::Moving);
  Validation v;
  v.effort_unit = "mA";
  v.estimate_names = {"nominal model"};
  v.effort = {{regime_stats(residual, labels)}};
  v.sensor.resize(1);
  const std::string text = validation_text(v);
  EXPECT_EQ(text.find("nan"), std::string::npos) << text;
  EXPECT_NE(text.find("  joint 1" + std::string(35, ' ') + "-" + std::string(18, ' ') + "-" +
                      "    0.200    0.200\n"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("-: no held-out sample in this regime"), std::string::npos) << text;
}

}  // namespace
}  // namespace tpf::offline
