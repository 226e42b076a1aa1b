// Prismatic joints in the dynamics: a hand-computable lift, the identities that need no reference
// (M from RNEA columns, the energy balance with a kinetic energy from link velocities, regressor
// times parameters, Ṁ = C + Cᵀ, forward dynamics inverting RNEA), the base parameters, and an
// 8-joint mobile arm (prismatic torso + 7 revolute, cut from a tree) at Eigen::Dynamic and N = 8.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <random>

#include "support/arm_fixture.hpp"
#include "support/mobile_arm.hpp"
#include "support/random_arm.hpp"
#include "support/temp_dir.hpp"
#include "tpf/estimation/link_parameters.hpp"

namespace tpf::test {
namespace {

using PrismaticModel = Model<double, Eigen::Dynamic>;
using PrismaticData = Data<double, Eigen::Dynamic>;

/// A random 6-joint arm whose joints 1, 3 and 6 are prismatic (the first, a middle and the last).
PrismaticModel prismatic_arm() {
  PrismaticModel model = random_arm(6, 2024);
  for (const int k : {0, 2, 5})
    model.joint_types[k] = JointType::prismatic;
  model.update_constants();
  return model;
}

Eigen::VectorXd uniform(std::mt19937_64& rng, int n, double scale) {
  std::uniform_real_distribution<double> u(-scale, scale);
  Eigen::VectorXd v(n);
  for (int j = 0; j < n; ++j)
    v(j) = u(rng);
  return v;
}

/// Kinetic energy from link velocities (the Jacobian at each centre of mass), not from M:
/// T = Σ ½ m |v_c|² + ½ ωᵀ I_c ω + ½ Σ armature q̇².
double kinetic_energy_of_links(const PrismaticModel& model, const Eigen::VectorXd& q,
                               const Eigen::VectorXd& dq) {
  PrismaticData data(model);
  forward_kinematics(model, data, q);
  double T = 0.5 * dq.dot(model.armature.cwiseProduct(dq));
  for (int k = 1; k <= model.joint_count(); ++k) {
    const Inertia<double>& body = model.inertias[k];
    const Vector3<double> c = data.oMi[k].apply(body.com);
    const Vector6<double> twist = point_jacobian(model, data, k, c) * dq;
    const Matrix3<double> I = data.oMi[k].R * body.rotational * data.oMi[k].R.transpose();
    T += 0.5 * body.mass * twist.head<3>().squaredNorm() +
         0.5 * twist.tail<3>().dot(I * twist.tail<3>());
  }
  return T;
}

TEST(Prismatic, AVerticalLiftCarriesMassTimesAccelerationPlusGravityAndItsArmature) {
  // One prismatic joint along z carrying m = 3 kg (its centre of mass anywhere), armature 0.5 kg.
  Model<double, 1> lift;
  lift.joint_types[0] = JointType::prismatic;
  lift.axes[0] = Vector3<double>::UnitZ();
  lift.inertias[1].mass = 3.0;
  lift.inertias[1].com = {0.1, -0.2, 0.3};
  lift.inertias[1].rotational = 0.01 * Matrix3<double>::Identity();
  lift.armature(0) = 0.5;
  lift.update_constants();
  Data<double, 1> data;
  const double g = 9.81;
  for (const double ddq : {-2.0, 0.0, 1.5}) {
    const JointVector<double, 1> q(0.2), dq(0.7), a(ddq);
    EXPECT_NEAR(rnea(lift, data, q, dq, a)(0), 3.0 * (ddq + g) + 0.5 * ddq, 1e-12);
  }
  EXPECT_NEAR(compute_gravity(lift, data, JointVector<double, 1>(0.3))(0), 3.0 * g, 1e-12);
  EXPECT_NEAR(compute_mass_matrix(lift, data, JointVector<double, 1>(0.3))(0, 0), 3.5, 1e-12);
  // Forward dynamics: a 50 N push on top of the weight accelerates 3.5 kg.
  const JointVector<double, 1> f(3.0 * g + 50.0);
  EXPECT_NEAR(
      forward_dynamics(lift, data, JointVector<double, 1>(0.1), JointVector<double, 1>(0), f)(0),
      50.0 / 3.5, 1e-12);
  // Potential energy: the centre of mass rises by Δq.
  EXPECT_NEAR(potential_energy(lift, data, JointVector<double, 1>(0.5)) -
                  potential_energy(lift, data, JointVector<double, 1>(0.2)),
              3.0 * g * 0.3, 1e-12);
  // Along the horizontal x axis gravity does no work.
  lift.axes[0] = Vector3<double>::UnitX();
  lift.update_constants();
  EXPECT_NEAR(compute_gravity(lift, data, JointVector<double, 1>(0.3))(0), 0.0, 1e-15);
}

TEST(Prismatic, ALiftBelowARevoluteLinkCarriesTheWholeMassAndTheLinksSwing) {
  // Joint 1 slides along z, joint 2 turns about z at the slider: a horizontal swing does not
  // load the lift beyond the weight, and joint 2 feels no gravity.
  Model<double, 2> m;
  m.joint_types[0] = JointType::prismatic;
  m.axes[0] = m.axes[1] = Vector3<double>::UnitZ();
  m.inertias[1].mass = 2.0;
  m.inertias[2].mass = 1.5;
  m.inertias[2].com = {0.4, 0.0, 0.0};
  m.update_constants();
  Data<double, 2> data;
  const Eigen::Vector2d q(0.3, 0.9), dq(0.4, 2.0), ddq(1.0, 0.0);
  const Eigen::Vector2d tau = rnea(m, data, q, dq, ddq);
  EXPECT_NEAR(tau(0), 3.5 * (1.0 + 9.81), 1e-12);
  EXPECT_NEAR(tau(1), 0.0, 1e-12);
}

TEST(Prismatic, MassMatrixColumnsAreRneaWithUnitAccelerations) {
  const PrismaticModel model = prismatic_arm();
  PrismaticData data(model);
  std::mt19937_64 rng(3);
  const int n = model.joint_count();
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::VectorXd q = uniform(rng, n, 2.0);
    const Eigen::MatrixXd M = compute_mass_matrix(model, data, q);
    const Eigen::VectorXd bias =
        rnea(model, data, q, Eigen::VectorXd::Zero(n), Eigen::VectorXd::Zero(n));
    for (int j = 0; j < n; ++j) {
      const Eigen::VectorXd column =
          rnea(model, data, q, Eigen::VectorXd::Zero(n), Eigen::VectorXd::Unit(n, j)) - bias;
      EXPECT_LT((column - M.col(j)).norm(), 1e-12 * M.norm()) << "column " << j;
    }
    EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(M).eigenvalues().minCoeff(), 0.0);
  }
}

TEST(Prismatic, KineticEnergyFromLinkVelocitiesIsHalfQdotMQdot) {
  const PrismaticModel model = prismatic_arm();
  PrismaticData data(model);
  std::mt19937_64 rng(4);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::VectorXd q = uniform(rng, 6, 2.0), dq = uniform(rng, 6, 1.5);
    const double T = kinetic_energy_of_links(model, q, dq);
    EXPECT_NEAR(kinetic_energy(model, data, q, dq), T, 1e-12 * T);
  }
}

TEST(Prismatic, PowerOfTheJointEffortsIsTheRateOfTheTotalEnergy) {
  // d/dt (T + V) = q̇ᵀ τ along q(t) = q + q̇ t + ½ q̈ t², with T from link velocities and V from
  // the link poses: the RNEA's efforts (N at the prismatic joints) against an energy balance.
  const PrismaticModel model = prismatic_arm();
  PrismaticData data(model);
  std::mt19937_64 rng(5);
  const double h = 1e-5;
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::VectorXd q = uniform(rng, 6, 2.0), dq = uniform(rng, 6, 1.5),
                          ddq = uniform(rng, 6, 3.0);
    const auto energy = [&](double t) {
      const Eigen::VectorXd qt = q + dq * t + 0.5 * ddq * t * t, dqt = dq + ddq * t;
      return kinetic_energy_of_links(model, qt, dqt) + potential_energy(model, data, qt);
    };
    const double rate = (energy(h) - energy(-h)) / (2 * h);
    const double power = dq.dot(rnea(model, data, q, dq, ddq));
    EXPECT_NEAR(power, rate, 1e-6 * (1.0 + std::abs(power))) << "trial " << trial;
    // and without gravity's share: q̇ᵀ(τ − G) = dT/dt
    const Eigen::VectorXd gravity = compute_gravity(model, data, q);
    const double kinetic_rate =
        (kinetic_energy_of_links(model, q + dq * h + 0.5 * ddq * h * h, dq + ddq * h) -
         kinetic_energy_of_links(model, q - dq * h + 0.5 * ddq * h * h, dq - ddq * h)) /
        (2 * h);
    const Eigen::VectorXd tau = rnea(model, data, q, dq, ddq);
    EXPECT_NEAR(dq.dot(tau - gravity), kinetic_rate, 1e-6 * (1.0 + std::abs(kinetic_rate)));
  }
}

TEST(Prismatic, GravityIsTheGradientOfThePotentialEnergy) {
  const PrismaticModel model = prismatic_arm();
  PrismaticData data(model);
  std::mt19937_64 rng(6);
  const double h = 1e-6;
  for (int trial = 0; trial < 10; ++trial) {
    const Eigen::VectorXd q = uniform(rng, 6, 2.0);
    const Eigen::VectorXd G = compute_gravity(model, data, q);
    for (int j = 0; j < 6; ++j) {
      const Eigen::VectorXd e = h * Eigen::VectorXd::Unit(6, j);
      const double dV =
          (potential_energy(model, data, q + e) - potential_energy(model, data, q - e)) / (2 * h);
      EXPECT_NEAR(G(j), dV, 1e-7) << "joint " << j + 1;
    }
  }
}

TEST(Prismatic, RegressorTimesParametersIsRnea) {
  const PrismaticModel model = prismatic_arm();
  PrismaticData data(model);
  std::mt19937_64 rng(7);
  const Eigen::VectorXd coulomb = Eigen::VectorXd::Constant(6, 4.0);
  const Eigen::VectorXd viscous = Eigen::VectorXd::Constant(6, 20.0);
  const Eigen::VectorXd pi = dynamic_parameters(model, coulomb, viscous);
  Regressor<double, Eigen::Dynamic> Y;
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::VectorXd q = uniform(rng, 6, 2.0), dq = uniform(rng, 6, 1.5),
                          ddq = uniform(rng, 6, 3.0);
    compute_regressor(model, data, q, dq, ddq, Y);
    Eigen::VectorXd expected = rnea(model, data, q, dq, ddq);
    for (int j = 0; j < 6; ++j)
      expected(j) += coulomb(j) * (dq(j) > 0 ? 1.0 : -1.0) + viscous(j) * dq(j);
    EXPECT_LT((Y * pi - expected).cwiseAbs().maxCoeff(), 1e-10) << "trial " << trial;
  }
}

TEST(Prismatic, LinkParameterTorqueOfTheEstimatorIsRneaAndGravity) {
  const PrismaticModel model = prismatic_arm();
  PrismaticData data(model), reference(model);
  std::mt19937_64 rng(11);
  const Eigen::VectorXd coulomb = Eigen::VectorXd::Constant(6, 4.0);
  const Eigen::VectorXd viscous = Eigen::VectorXd::Constant(6, 20.0);
  const LinkParameters<double, Eigen::Dynamic> links =
      link_parameters<double, Eigen::Dynamic>(dynamic_parameters(model, coulomb, viscous));
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::VectorXd q = uniform(rng, 6, 2.0), dq = uniform(rng, 6, 1.5),
                          ddq = uniform(rng, 6, 3.0);
    forward_kinematics(model, data, q);
    const Eigen::VectorXd tau = link_parameter_torque(model, links, data, dq, ddq);
    Eigen::VectorXd expected = rnea(model, reference, q, dq, ddq);
    for (int j = 0; j < 6; ++j)
      expected(j) += coulomb(j) * (dq(j) > 0 ? 1.0 : -1.0) + viscous(j) * dq(j);
    EXPECT_LT((tau - expected).cwiseAbs().maxCoeff(), 1e-10) << "trial " << trial;
    const Eigen::VectorXd g = link_parameter_gravity(model, links, data);
    EXPECT_LT((g - compute_gravity(model, reference, q)).cwiseAbs().maxCoeff(), 1e-10);
  }
}

TEST(Prismatic, CoriolisMatrixGivesTheRateOfTheMassMatrix) {
  const PrismaticModel model = prismatic_arm();
  PrismaticData data(model);
  std::mt19937_64 rng(8);
  const double h = 1e-6;
  for (int trial = 0; trial < 10; ++trial) {
    const Eigen::VectorXd q = uniform(rng, 6, 2.0), dq = uniform(rng, 6, 1.5);
    const Eigen::MatrixXd M_plus = compute_mass_matrix(model, data, q + h * dq);
    const Eigen::MatrixXd M_minus = compute_mass_matrix(model, data, q - h * dq);
    const Eigen::MatrixXd C = compute_coriolis_matrix(model, data, q, dq);
    EXPECT_LT((C + C.transpose() - (M_plus - M_minus) / (2 * h)).norm(), 1e-7);
    // and C q̇ is the velocity part of RNEA
    const Eigen::VectorXd c = velocity_torques(model, data, q, dq);
    EXPECT_LT((C * dq - c).norm(), 1e-10 * (1.0 + c.norm()));
  }
}

TEST(Prismatic, ForwardDynamicsInvertsRneaAndTheExternalWrenchMapsThroughTheJacobian) {
  const PrismaticModel model = prismatic_arm();
  PrismaticData data(model);
  std::mt19937_64 rng(9);
  for (int trial = 0; trial < 10; ++trial) {
    const Eigen::VectorXd q = uniform(rng, 6, 2.0), dq = uniform(rng, 6, 1.5),
                          ddq = uniform(rng, 6, 3.0);
    const Eigen::VectorXd tau = rnea(model, data, q, dq, ddq);
    EXPECT_LT((forward_dynamics(model, data, q, dq, tau) - ddq).norm(), 1e-9);
    const int link = 1 + trial % 6;
    forward_kinematics(model, data, q);
    const Vector3<double> p = data.oMi[link].apply(Vector3<double>(0.05, -0.1, 0.2));
    Vector6<double> w;
    w << 10.0, -4.0, 7.0, 0.5, 1.0, -2.0;
    const Eigen::MatrixXd J = point_jacobian(model, data, link, p);
    const Eigen::VectorXd with_wrench = rnea(model, data, q, dq, ddq, link, p, w);
    EXPECT_LT((with_wrench - (tau - J.transpose() * w)).norm(), 1e-10);
  }
}

/// The stacked regressor of `model` at `samples` random states.
template <int N>
Eigen::MatrixXd stacked(const Model<double, N>& model, int samples, unsigned seed) {
  Data<double, N> data(model);
  const int n = model.joint_count();
  std::mt19937_64 rng(seed);
  Regressor<double, N> Y;
  Eigen::MatrixXd W(samples * n, 13 * n);
  for (int s = 0; s < samples; ++s) {
    const JointVector<double, N> q = uniform(rng, n, 2.0), dq = uniform(rng, n, 1.5),
                                 ddq = uniform(rng, n, 3.0);
    compute_regressor(model, data, q, dq, ddq, Y);
    W.middleRows(s * n, n) = Y;
  }
  return W;
}

TEST(Prismatic, AVerticalLiftHasFourBaseParameters) {
  // Y = [q̈ + g, 0 … 0 | q̈ | sgn q̇ | q̇]: the mass, the armature and the two friction terms.
  Model<double, 1> lift;
  lift.joint_types[0] = JointType::prismatic;
  lift.axes[0] = Vector3<double>::UnitZ();
  lift.inertias[1].mass = 3.0;
  lift.update_constants();
  const BaseParameters base = find_base_parameters(stacked(lift, 50, 1));
  EXPECT_EQ(base.independent, (std::vector<int>{0, 10, 11, 12}));
}

TEST(Prismatic, BaseParametersReproduceTheEffortsAtDynamicAndFixedCount) {
  const PrismaticModel dynamic = prismatic_arm();
  Model<double, 6> fixed = joint_count_cast<6>(dynamic);
  const Eigen::MatrixXd W_dynamic = stacked(dynamic, 150, 21);
  const Eigen::MatrixXd W_fixed = stacked(fixed, 150, 21);
  EXPECT_LT((W_dynamic - W_fixed).cwiseAbs().maxCoeff(), 1e-12);
  const BaseParameters base = find_base_parameters(W_dynamic);
  const BaseParameters base_fixed = find_base_parameters(W_fixed);
  EXPECT_EQ(base.independent, base_fixed.independent);
  EXPECT_LT(base.size(), 13 * 6);
  const Eigen::VectorXd pi = dynamic_parameters(dynamic, Eigen::VectorXd::Constant(6, 2.0),
                                                Eigen::VectorXd::Constant(6, 9.0));
  const Eigen::MatrixXd fresh = stacked(dynamic, 40, 22);
  EXPECT_LT((base.reduce(fresh) * base.project(pi) - fresh * pi).norm(),
            1e-9 * (fresh * pi).norm());
}

const TempDir kFiles("prismatic_dynamics");

TEST(Prismatic, TheEightJointMobileArmGivesTheSameNumbersAtDynamicAndFixedCount) {
  const std::filesystem::path robot = write_mobile_arm(kFiles.path());
  const Model<double, 8> fixed = load_robot<double, 8>(robot);
  const PrismaticModel dynamic = load_robot<double, Eigen::Dynamic>(robot);
  ASSERT_EQ(dynamic.joint_count(), 8);
  ASSERT_TRUE(fixed.is_prismatic(0));
  Data<double, 8> fd(fixed);
  PrismaticData dd(dynamic);
  std::mt19937_64 rng(31);
  Regressor<double, 8> Yf;
  Regressor<double, Eigen::Dynamic> Yd;
  const auto near = [](const auto& a, const auto& b) {
    return (a - b).cwiseAbs().maxCoeff() <= 1e-12 * (1.0 + b.cwiseAbs().maxCoeff());
  };
  for (int trial = 0; trial < 20; ++trial) {
    const JointVector<double, 8> q = uniform(rng, 8, 2.0), dq = uniform(rng, 8, 1.5),
                                 ddq = uniform(rng, 8, 3.0), tau = uniform(rng, 8, 50.0);
    const Eigen::VectorXd qd = q, dqd = dq, ddqd = ddq, taud = tau;
    EXPECT_TRUE(near(rnea(dynamic, dd, qd, dqd, ddqd), rnea(fixed, fd, q, dq, ddq)));
    EXPECT_TRUE(near(compute_gravity(dynamic, dd, qd), compute_gravity(fixed, fd, q)));
    EXPECT_TRUE(near(compute_mass_matrix(dynamic, dd, qd), compute_mass_matrix(fixed, fd, q)));
    EXPECT_TRUE(near(compute_coriolis_matrix(dynamic, dd, qd, dqd),
                     compute_coriolis_matrix(fixed, fd, q, dq)));
    EXPECT_TRUE(near(forward_dynamics(dynamic, dd, qd, dqd, taud),
                     forward_dynamics(fixed, fd, q, dq, tau)));
    EXPECT_NEAR(kinetic_energy(dynamic, dd, qd, dqd), kinetic_energy(fixed, fd, q, dq), 1e-12);
    compute_regressor(dynamic, dd, qd, dqd, ddqd, Yd);
    compute_regressor(fixed, fd, q, dq, ddq, Yf);
    EXPECT_TRUE(near(Yd, Yf));
    forward_kinematics(dynamic, dd, qd);
    forward_kinematics(fixed, fd, q);
    const Vector3<double> p = fd.oMi[8].apply(Vector3<double>(0.1, 0.0, 0.02));
    EXPECT_TRUE(near(point_jacobian(dynamic, dd, 8, p), point_jacobian(fixed, fd, 8, p)));
  }
}

}  // namespace
}  // namespace tpf::test
