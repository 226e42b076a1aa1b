// `tpf import` of a log as an industrial arm records it: two files (motor positions, motor
// torques), no time column, motor side with signed gear ratios and a coupled wrist, an encoder
// offset and a flipped sign. The files are written here from known joint trajectories; the
// import must give back q, q̇ (derived from q), q̈ and the joint torques.
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "log_test_files.hpp"
#include "offline/log/import_log.hpp"
#include "tpf/common/error.hpp"

namespace tpf::offline {
namespace {

using test::TempDir;
using test::write_text;

constexpr int kJoints = 6;
constexpr double kRate = 1000.0;
constexpr int kRows = 3000;

/// Joint j's known trajectory: q = a·sin(ω t + φ) + c, and its joint torque.
struct Trajectory {
  double a, w, phase, centre;
  double q(double t) const { return a * std::sin(w * t + phase) + centre; }
  double dq(double t) const { return a * w * std::cos(w * t + phase); }
  double ddq(double t) const { return -a * w * w * std::sin(w * t + phase); }
  double tau(double t) const { return 3.0 * a * std::cos(0.7 * w * t) + centre; }
};

Trajectory trajectory(int j) {
  return {0.3 + 0.1 * j, 2.0 * std::numbers::pi * (0.4 + 0.15 * j), 0.5 * j, 0.2 * j - 0.4};
}

/// R = diag(ratio)·coupling: the last motor rotates with q5 + q6.
Eigen::MatrixXd transmission() {
  Eigen::VectorXd ratio(kJoints);
  ratio << 32, 32, 45, -48, 45, 32;
  Eigen::MatrixXd coupling = Eigen::MatrixXd::Identity(kJoints, kJoints);
  coupling(5, 4) = 1.0;
  return ratio.asDiagonal() * coupling;
}

constexpr double kOffset = 0.25;  // encoder zero of motor 2 [rad]; the map removes it
constexpr int kFlipped = 3;       // motor 3's position and torque are written with sign −1

const char* kCoupledWristMap =
    R"({"format": "tpf-import", "version": 1, "joints": 6, "rate_hz": 1000,
  "files": 2, "join": "index",
  "time": {"unit": "rate"},
  "transmission": {"ratio": [32, 32, 45, -48, 45, 32],
                   "coupling": [[1,0,0,0,0,0],[0,1,0,0,0,0],[0,0,1,0,0,0],
                                [0,0,0,1,0,0],[0,0,0,0,1,0],[0,0,0,0,1,1]]},
  "derive": {"cutoff_hz": 20},
  "columns": {"q": {"source": "enc{j}", "unit": "rad", "side": "motor",
                    "sign": [1, 1, -1, 1, 1, 1], "offset": [0, -0.25, 0, 0, 0, 0]},
              "tau": {"source": "trq{j}", "unit": "mN*m", "side": "motor",
                      "sign": [1, 1, -1, 1, 1, 1]}}})";

/// Writes positions.csv (motor angles) and torques.csv (motor torques in mN·m), no time column.
void write_recording(const std::filesystem::path& dir) {
  const Eigen::MatrixXd r = transmission();
  const Eigen::MatrixXd r_inv_t = r.transpose().inverse();
  std::string positions = "enc1,enc2,enc3,enc4,enc5,enc6,status\n";
  std::string torques = "trq1,trq2,trq3,trq4,trq5,trq6\n";
  char field[40];
  for (int k = 0; k < kRows; ++k) {
    const double t = k / kRate;
    Eigen::VectorXd q(kJoints), tau(kJoints);
    for (int j = 0; j < kJoints; ++j) {
      q[j] = trajectory(j).q(t);
      tau[j] = trajectory(j).tau(t);
    }
    Eigen::VectorXd motor = r * q;
    Eigen::VectorXd motor_tau = 1000.0 * r_inv_t * tau;  // τ_joint = Rᵀ·τ_motor, in mN·m
    motor[1] += kOffset;
    motor[kFlipped - 1] *= -1.0;
    motor_tau[kFlipped - 1] *= -1.0;
    for (int j = 0; j < kJoints; ++j) {
      std::snprintf(field, sizeof field, "%.17g,", motor[j]);
      positions += field;
      std::snprintf(field, sizeof field, j + 1 < kJoints ? "%.17g," : "%.17g\n", motor_tau[j]);
      torques += field;
    }
    positions += "ok\n";
  }
  write_text(dir / "positions.csv", positions);
  write_text(dir / "torques.csv", torques);
}

TEST(ImportTransmission, TwoFileMotorSideCoupledWristLogGivesBackTheJointTrajectories) {
  TempDir dir("import_transmission");
  write_text(dir / "map.json", kCoupledWristMap);
  write_recording(dir.path());
  const ImportMap map = load_import_map(dir / "map.json");
  EXPECT_TRUE(map.coupled);
  ImportReport report;
  const Log log = import_log({dir / "positions.csv", dir / "torques.csv"}, map, report);
  ASSERT_EQ(log.rows(), kRows);
  EXPECT_EQ(log.columns.size(), 1u + 4u * kJoints);  // t, q, dq (derived), ddq (derived), tau
  EXPECT_DOUBLE_EQ(log.col("t")[kRows - 1], (kRows - 1) / kRate);
  double q_err = 0, tau_err = 0, dq_err = 0, ddq_err = 0, dq_scale = 0, ddq_scale = 0;
  // q̇ and q̈ are checked away from the ends, where the filter's reflected padding is felt
  const int margin = static_cast<int>(0.1 * kRate);
  for (int j = 0; j < kJoints; ++j) {
    const Trajectory tr = trajectory(j);
    dq_scale = std::max(dq_scale, tr.a * tr.w);
    ddq_scale = std::max(ddq_scale, tr.a * tr.w * tr.w);
    for (int k = 0; k < kRows; ++k) {
      const double t = k / kRate;
      q_err = std::max(q_err, std::abs(log.col(indexed_name("q", j + 1))[k] - tr.q(t)));
      tau_err = std::max(tau_err, std::abs(log.col(indexed_name("tau", j + 1))[k] - tr.tau(t)));
      if (k < margin || k >= kRows - margin) continue;
      dq_err = std::max(dq_err, std::abs(log.col(indexed_name("dq", j + 1))[k] - tr.dq(t)));
      ddq_err = std::max(ddq_err, std::abs(log.col(indexed_name("ddq", j + 1))[k] - tr.ddq(t)));
    }
    EXPECT_TRUE(std::isnan(log.col(indexed_name("dq", j + 1))[0]));  // no one-sided difference
  }
  EXPECT_LT(q_err, 1e-12);
  EXPECT_LT(tau_err, 1e-9);
  // 20 Hz zero-phase Butterworth on ≤ 1.15 Hz motion at 1 kHz: gain and difference errors
  // below 1e-4 of the largest velocity, 1e-3 of the largest acceleration
  EXPECT_LT(dq_err, 1e-4 * dq_scale) << dq_err;
  EXPECT_LT(ddq_err, 1e-3 * ddq_scale) << ddq_err;
  bool said_transmission = false;
  for (const std::string& line : report.lines())
    said_transmission = said_transmission || line.find("diag(ratio)*coupling") != std::string::npos;
  EXPECT_TRUE(said_transmission);
}

TEST(ImportTransmission, FilesOfDifferentLengthsJoinedByIndexAreRefused) {
  TempDir dir("import_transmission");
  write_text(dir / "map.json", kCoupledWristMap);
  write_recording(dir.path());
  write_text(dir / "short.csv", "trq1,trq2,trq3,trq4,trq5,trq6\n1,2,3,4,5,6\n");
  const ImportMap map = load_import_map(dir / "map.json");
  ImportReport report;
  try {
    import_log({dir / "positions.csv", dir / "short.csv"}, map, report);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("short.csv: 1 data rows"), std::string::npos) << e.what();
  }
}

TEST(ImportTransmission, FilesJoinedByTimeKeepTheSamplesEveryFileHas) {
  TempDir dir("import_transmission");
  write_text(dir / "map.json", R"({"format": "tpf-import", "version": 1, "joints": 1,
    "files": 2, "join": "time", "time": {"column": "t", "unit": "s"},
    "columns": {"q": {"source": "pos", "unit": "mm"}, "dq": {"source": "vel", "unit": "mm/s"},
                "i": {"source": "cur", "unit": "A", "torque_constant": -0.5, "side": "motor"}},
    "transmission": {"ratio": [4]}})");
  write_text(dir / "a.csv", "t,pos,vel\n0,1,10\n0.01,2,10\n0.02,3,10\n0.03,4,10\n");
  write_text(dir / "b.csv", "t,cur\n0.0,1\n0.0201,2\n0.03,3\n0.05,9\n");
  const ImportMap map = load_import_map(dir / "map.json");
  ImportReport report;
  const Log log = import_log({dir / "a.csv", dir / "b.csv"}, map, report);
  ASSERT_EQ(log.rows(), 3);  // 0.01 has no current sample within a quarter step
  EXPECT_EQ(report.unmatched_rows, 1u);
  EXPECT_DOUBLE_EQ(log.col("t")[1], 0.02);
  EXPECT_DOUBLE_EQ(log.col("q1")[2], 0.004);
  EXPECT_DOUBLE_EQ(log.col("dq1")[0], 0.01);
  // output-side constant 4·(−0.5) < 0: the current's sign is turned to follow the joint torque
  EXPECT_DOUBLE_EQ(log.col("i1")[1], -2000.0);
}

TEST(ImportTransmission, ACoupledTransmissionsCurrentMustBeWrittenAsTorque) {
  TempDir dir("import_transmission");
  std::string map = kCoupledWristMap;
  map.replace(map.find("\"tau\": {\"source\": \"trq{j}\", \"unit\": \"mN*m\""),
              std::string("\"tau\": {\"source\": \"trq{j}\", \"unit\": \"mN*m\"").size(),
              "\"i\": {\"source\": \"trq{j}\", \"unit\": \"A\", \"torque_constant\": 0.1");
  write_text(dir / "map.json", map);
  try {
    load_import_map(dir / "map.json");
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("\"write\": \"torque\""), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace tpf::offline
