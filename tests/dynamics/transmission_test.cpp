// Coupled transmissions in the dynamics: motor m turns with (C·q)_m, its rotor adds
// Cᵀ·diag(armature)·C to M, its friction acts as Cᵀ·f(C·q̇). Checked against explicit matrix
// forms written here (not the library's loops), identities that need no reference (M from RNEA
// columns, forward dynamics inverting RNEA, the regressor and the link-parameter form agreeing),
// the identity coupling giving the uncoupled model bit for bit, and the robot file's coupled_to.
#include <gtest/gtest.h>

#include <fstream>
#include <random>
#include <sstream>

#include "support/random_arm.hpp"
#include "support/temp_dir.hpp"
#include "tpf/common/error.hpp"
#include "tpf/dynamics/forward_dynamics.hpp"
#include "tpf/dynamics/mass_matrix.hpp"
#include "tpf/dynamics/regressor.hpp"
#include "tpf/dynamics/rnea.hpp"
#include "tpf/estimation/link_parameters.hpp"
#include "tpf/model/load_robot.hpp"

namespace tpf::test {
namespace {

using CoupledModel = Model<double, Eigen::Dynamic>;
using CoupledData = Data<double, Eigen::Dynamic>;

/// `model` with rotors on every joint and, if `couple`, motor 6 turning with q5 + q6 (a
/// differential wrist) and motor 5 with q5 − 0.5·q4.
CoupledModel coupled_arm_of(CoupledModel model, bool couple) {
  model.armature << 0.8, 0.7, 0.4, 0.2, 0.15, 0.1;
  if (!couple) return model;
  Eigen::MatrixXd c = Eigen::MatrixXd::Identity(6, 6);
  c(5, 4) = 1.0;
  c(4, 3) = -0.5;
  model.set_coupling(c);
  return model;
}

/// A random 6-joint arm, coupled as coupled_arm_of says.
CoupledModel coupled_arm() {
  return coupled_arm_of(random_arm(6, 77), true);
}

Eigen::VectorXd random_vector(std::mt19937_64& rng, int n, double scale) {
  std::uniform_real_distribution<double> u(-scale, scale);
  Eigen::VectorXd v(n);
  for (int j = 0; j < n; ++j)
    v(j) = u(rng);
  return v;
}

/// The same arm without rotors: its rigid body alone.
CoupledModel without_rotors(CoupledModel model) {
  model.armature.setZero();
  return model;
}

TEST(Transmission, RneaAddsTheRotorsThroughTheCoupling) {
  const CoupledModel model = coupled_arm();
  const CoupledModel rigid = without_rotors(model);
  const Eigen::MatrixXd& C = model.coupling;
  CoupledData data(model), rigid_data(rigid);
  std::mt19937_64 rng(1);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::VectorXd q = random_vector(rng, 6, 2.0), dq = random_vector(rng, 6, 1.5),
                          ddq = random_vector(rng, 6, 3.0);
    const Eigen::VectorXd tau = rnea(model, data, q, dq, ddq);
    const Eigen::VectorXd expected =
        rnea(rigid, rigid_data, q, dq, ddq) + C.transpose() * model.armature.asDiagonal() * C * ddq;
    EXPECT_LT((tau - expected).norm(), 1e-12 * (1 + expected.norm()));
  }
}

TEST(Transmission, MassMatrixIsTheRnea_sColumnsAndHoldsCTransposeDiagC) {
  const CoupledModel model = coupled_arm();
  const CoupledModel rigid = without_rotors(model);
  CoupledData data(model), rigid_data(rigid);
  std::mt19937_64 rng(2);
  const Eigen::VectorXd q = random_vector(rng, 6, 2.0);
  const Eigen::MatrixXd M = compute_mass_matrix(model, data, q);
  const Eigen::VectorXd bias =
      rnea(model, data, q, Eigen::VectorXd::Zero(6), Eigen::VectorXd::Zero(6));
  for (int i = 0; i < 6; ++i) {
    const Eigen::VectorXd column =
        rnea(model, data, q, Eigen::VectorXd::Zero(6), Eigen::VectorXd::Unit(6, i)) - bias;
    EXPECT_LT((M.col(i) - column).norm(), 1e-12) << "column " << i;
  }
  const Eigen::MatrixXd rotors = M - compute_mass_matrix(rigid, rigid_data, q);
  const Eigen::MatrixXd expected =
      model.coupling.transpose() * model.armature.asDiagonal() * model.coupling;
  EXPECT_LT((rotors - expected).norm(), 1e-12);
  EXPECT_NE(rotors(4, 5), 0.0);  // the wrist's rotor couples joints 5 and 6
  EXPECT_LT((M - M.transpose()).norm(), 1e-12);
}

TEST(Transmission, ForwardDynamicsInvertsRnea) {
  const CoupledModel model = coupled_arm();
  CoupledData data(model);
  std::mt19937_64 rng(3);
  const Eigen::VectorXd q = random_vector(rng, 6, 2.0), dq = random_vector(rng, 6, 1.0),
                        ddq = random_vector(rng, 6, 2.0);
  const Eigen::VectorXd tau = rnea(model, data, q, dq, ddq);
  const Eigen::VectorXd back = forward_dynamics(model, data, q, dq, tau);
  EXPECT_LT((back - ddq).norm(), 1e-10);
}

TEST(Transmission, RegressorTakesEachMotorsArmatureAndFrictionOnItsOwnRates) {
  const CoupledModel model = coupled_arm();
  const Eigen::MatrixXd& C = model.coupling;
  CoupledData data(model);
  std::mt19937_64 rng(4);
  Eigen::VectorXd coulomb(6), viscous(6);
  coulomb << 3, 2.5, 2, 1, 0.8, 0.6;
  viscous << 1.2, 1, 0.8, 0.4, 0.3, 0.2;
  const Eigen::VectorXd pi = dynamic_parameters(model, coulomb, viscous);
  const LinkParameters<double, Eigen::Dynamic> links = link_parameters<double, Eigen::Dynamic>(pi);
  Regressor<double, Eigen::Dynamic> Y(6, 13 * 6);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::VectorXd q = random_vector(rng, 6, 2.0), dq = random_vector(rng, 6, 1.5),
                          ddq = random_vector(rng, 6, 3.0);
    compute_regressor(model, data, q, dq, ddq, Y);
    const Eigen::VectorXd motor_rate = C * dq;
    const Eigen::VectorXd friction =
        coulomb.cwiseProduct(motor_rate.array().sign().matrix()) + viscous.cwiseProduct(motor_rate);
    const Eigen::VectorXd expected = rnea(model, data, q, dq, ddq) + C.transpose() * friction;
    EXPECT_LT((Y * pi - expected).norm(), 1e-10 * (1 + expected.norm()));
    const Eigen::VectorXd by_links = link_parameter_torque(model, links, data, dq, ddq);
    EXPECT_LT((by_links - expected).norm(), 1e-10 * (1 + expected.norm()));
  }
}

TEST(Transmission, TheIdentityCouplingIsTheUncoupledModelBitForBit) {
  const CoupledModel plain = coupled_arm_of(random_arm(6, 77), false);
  CoupledModel model = coupled_arm_of(plain, true);
  ASSERT_TRUE(model.coupled);
  model.set_coupling(Eigen::MatrixXd::Identity(6, 6));
  EXPECT_FALSE(model.coupled);
  CoupledData a(model), b(plain);
  const Eigen::VectorXd q = Eigen::VectorXd::LinSpaced(6, -1, 1), dq = q.reverse(), ddq = 2 * q;
  EXPECT_EQ(rnea(model, a, q, dq, ddq), rnea(plain, b, q, dq, ddq));
  EXPECT_EQ(compute_mass_matrix(model, a, q), compute_mass_matrix(plain, b, q));
}

// A robot file on a 3-joint URDF whose third motor is coupled as `coupled_to` says.
std::filesystem::path coupled_robot(const TempDir& dir, const std::string& coupled_to,
                                    const std::string& third_ratio = "-48") {
  std::ofstream(dir / "three.urdf") << R"(<robot name="three">
  <link name="base"/>
  <link name="l1"><inertial><mass value="2"/><origin xyz="0 0 0.1"/>
    <inertia ixx="0.02" iyy="0.02" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="l2"><inertial><mass value="1"/><origin xyz="0.1 0 0"/>
    <inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="l3"><inertial><mass value="0.5"/><origin xyz="0.05 0 0"/>
    <inertia ixx="0.005" iyy="0.005" izz="0.005" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/>
    <axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="50" velocity="2"/></joint>
  <joint name="j2" type="revolute"><parent link="l1"/><child link="l2"/><origin xyz="0 0 0.2"/>
    <axis xyz="0 1 0"/><limit lower="-3" upper="3" effort="50" velocity="2"/></joint>
  <joint name="j3" type="revolute"><parent link="l2"/><child link="l3"/><origin xyz="0.2 0 0"/>
    <axis xyz="1 0 0"/><limit lower="-3" upper="3" effort="50" velocity="2"/></joint>
</robot>)";
  const auto drive = [](const std::string& name, const std::string& ratio,
                        const std::string& extra) {
    std::ostringstream text;
    text << "{\"name\": \"" << name << "\", \"gear_ratio\": " << ratio
         << ", \"rotor_inertia\": 1e-5, \"torque_constant\": 2, \"current_limit\": 5000" << extra
         << "}";
    return text.str();
  };
  std::ofstream(dir / "three.robot.json")
      << R"({"format": "tpf-robot", "version": 1, "name": "three", "urdf": "three.urdf",
  "joints": [)"
      << drive("j1", "32", "") << ",\n"
      << drive("j2", "40", "") << ",\n"
      << drive("j3", third_ratio,
               coupled_to.empty() ? std::string() : ", \"coupled_to\": " + coupled_to)
      << "]}";
  return dir / "three.robot.json";
}

std::string load_error(const std::filesystem::path& file) {
  try {
    load_robot<double, Eigen::Dynamic>(file);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(Transmission, TheRobotFileCouplesAMotorToOtherJoints) {
  const TempDir dir("transmission_robot");
  const CoupledModel model =
      load_robot<double, Eigen::Dynamic>(coupled_robot(dir, R"({"j2": 1.0})"));
  ASSERT_TRUE(model.coupled);
  Eigen::Matrix3d expected = Eigen::Matrix3d::Identity();
  expected(2, 1) = 1.0;
  EXPECT_EQ(model.coupling, expected);
  EXPECT_EQ(model.gear_ratio(2), -48.0);                    // signed
  EXPECT_DOUBLE_EQ(model.armature(2), 1e-5 * 48.0 * 48.0);  // the rotor, reflected
  // Fixed N reads the same file to the same coupling.
  const Model<double, 3> fixed = load_robot<double, 3>(dir / "three.robot.json");
  EXPECT_TRUE(fixed.coupled);
  EXPECT_EQ(Eigen::Matrix3d(fixed.coupling), expected);
}

TEST(Transmission, BadCouplingsAreRefusedNamingTheFileAndField) {
  const TempDir dir("transmission_bad");
  std::string e = load_error(coupled_robot(dir, R"({"wrist": 1.0})"));
  EXPECT_NE(e.find("three.robot.json"), std::string::npos) << e;
  EXPECT_NE(e.find("wrist"), std::string::npos) << e;
  e = load_error(coupled_robot(dir, R"({"j3": 2.0})"));
  EXPECT_NE(e.find("own joint"), std::string::npos) << e;
  e = load_error(coupled_robot(dir, R"({"j2": "one"})"));
  EXPECT_NE(e.find("coupled_to"), std::string::npos) << e;
  e = load_error(coupled_robot(dir, "", "0"));
  EXPECT_NE(e.find("gear_ratio"), std::string::npos) << e;
  EXPECT_NE(e.find("must not be 0"), std::string::npos) << e;
}

TEST(Transmission, ToolsThatTakeFrictionPerJointRefuseACoupledRobot) {
  const TempDir dir("transmission_refused");
  const auto file = coupled_robot(dir, R"({"j2": 1.0})");
  const CoupledModel model = load_robot<double, Eigen::Dynamic>(file);
  try {
    require_uncoupled_drives(model, "diagnose");
    ADD_FAILURE() << "a coupled robot was accepted";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("three"), std::string::npos) << m;
    EXPECT_NE(m.find("coupled_to"), std::string::npos) << m;
    EXPECT_NE(m.find("diagnose"), std::string::npos) << m;
  }
  EXPECT_NO_THROW(require_uncoupled_drives(random_arm(3, 1), "diagnose"));
}

}  // namespace
}  // namespace tpf::test
