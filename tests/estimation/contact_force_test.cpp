// The contact force from joint torques: exact recovery where the arm observes it, the pad prior
// where it does not, and an honest validity flag where neither does.
#include "tpf/estimation/contact_force.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "support/arm_fixture.hpp"
#include "tpf/kinematics/point_jacobian.hpp"
#include "tpf/skin/skin.hpp"

namespace {

using tpf::test::angle_deg;
using tpf::test::arm;
using tpf::test::Vec;

struct Case {
  tpf::Jacobian<double, 4> J;
  tpf::Matrix3<double> R;
};

Case pad_case(const tpf::PadGeometry<double>& pad, const Vec& q) {
  tpf::test::ArmData data;
  tpf::forward_kinematics(arm(), data, q);
  Case c;
  c.J = tpf::point_jacobian(arm(), data, pad.link, tpf::pad_point_in_world(data, pad));
  c.R = tpf::contact_frame_in_world(data, pad.link, pad.normal);
  return c;
}

std::vector<tpf::Pad> pads() {
  return tpf::load_pads(tpf::test::data_path("arm4.pads.json"), arm());
}

tpf::PadGeometry<double> geometry(const tpf::Pad& p) {
  return {p.link, p.center, p.normal, p.area};
}

TEST(ContactForce, DistalPadRecoversNormalAndShearFromExactTorques) {
  const auto layout = pads();
  tpf::test::RandomStates random(21);
  int checked = 0;
  for (int trial = 0; trial < 50; ++trial) {
    const Vec q = random.vector(1.2);
    const tpf::PadGeometry<double> pad = geometry(layout[9]);  // distal_side, on the last link
    const Case c = pad_case(pad, q);
    // A push (f_z < 0 in the contact frame) with shear up to half of it.
    const tpf::Vector3<double> f_contact(random.point(0.5)[0] * 10, random.point(0.5)[1] * 10,
                                         -10.0);
    const tpf::Vector3<double> f_world = c.R * f_contact;
    const Vec tau = c.J.topRows<3>().transpose() * f_world;  // τ_ext = J_vᵀ f
    // Exact torques: a σ_τ of 1e-4 N·m says so (the shear prior then hardly matters).
    const auto est =
        tpf::estimate_contact_force<double, 4>(c.J, c.R, tau, Vec::Constant(1e-4), 10.0);
    if (!est.observable_by_arm) continue;  // singular poses are checked below
    ++checked;
    EXPECT_TRUE(est.valid);
    EXPECT_LT(angle_deg(est.force_world, f_world), 0.5);
    EXPECT_NEAR(est.force_world.norm(), f_world.norm(), 0.01 * f_world.norm());
    EXPECT_LT((c.R.transpose() * est.force_world - est.force_contact).norm(), 1e-9);
    EXPECT_GE(est.condition, 1.0);
    EXPECT_NEAR(est.inverse_condition * est.condition, 1.0, 1e-12);
  }
  EXPECT_GT(checked, 40);
}

TEST(ContactForce, ProximalPadUsesThePadReadingForTheNormal) {
  // Pads on link index 2 move with joints 1–2 only: the Jacobian has rank ≤ 2. For the front pad
  // the unobservable direction is mostly the normal, which the pad measures.
  const auto layout = pads();
  const tpf::PadGeometry<double> pad = geometry(layout[0]);
  ASSERT_EQ(pad.link, 2);
  const Vec q(0.3, -0.5, 0.4, 0.2);
  const Case c = pad_case(pad, q);
  const tpf::Vector3<double> f_contact(1.5, -2.0, -12.0);
  const Vec tau = c.J.topRows<3>().transpose() * (c.R * f_contact);
  // Exact torques (σ_τ = 1e-4 N·m) and no shear prior: the pad alone fills the unseen direction.
  tpf::ContactForceSettings<double> settings;
  settings.shear_relative = 1e6;
  const auto est =
      tpf::estimate_contact_force<double, 4>(c.J, c.R, tau, Vec::Constant(1e-4), 12.0, settings);
  EXPECT_FALSE(est.observable_by_arm);
  EXPECT_LT(est.inverse_condition, 1e-6);
  if (est.valid) {
    EXPECT_LT(angle_deg(est.force_world, c.R * f_contact), 2.0);
  } else {
    EXPECT_LT(est.shear_inverse_condition, 0.02);
  }
}

TEST(ContactForce, UnobservableContactIsFlaggedNotZeroed) {
  // A pad on link 1 moves with joint 1 only: one torque for three force components.
  tpf::PadGeometry<double> pad{1, tpf::Vector3<double>(0.05, 0.0, 0.05),
                               tpf::Vector3<double>(1, 0, 0), 0.002};
  const Case c = pad_case(pad, Vec(0.2, 0.1, -0.3, 0.4));
  const Vec tau = c.J.topRows<3>().transpose() * (c.R * tpf::Vector3<double>(3, 2, -8));
  const auto est = tpf::estimate_contact_force<double, 4>(c.J, c.R, tau, 8.0);
  EXPECT_FALSE(est.valid);
  EXPECT_FALSE(est.observable_by_arm);
  EXPECT_LT(est.inverse_condition, 1e-6);
  EXPECT_LT(est.shear_inverse_condition, 1e-6);
  EXPECT_TRUE(std::isinf(est.condition));
  EXPECT_TRUE(est.force_contact.allFinite());
  EXPECT_GT(est.force_contact.norm(), 1.0);  // still the least-squares answer, not zeros
}

// The solve is the maximum a posteriori force: the same as stacking the weighted torque rows and
// the prior rows and solving by QR, with the posterior std from the normal matrix.
TEST(ContactForce, EqualsTheStackedWeightedLeastSquaresWithItsPosteriorStd) {
  const auto layout = pads();
  tpf::test::RandomStates random(5);
  tpf::ContactForceSettings<double> settings;
  for (int trial = 0; trial < 20; ++trial) {
    const tpf::PadGeometry<double> pad = geometry(layout[static_cast<std::size_t>(trial % 11)]);
    const Case c = pad_case(pad, random.vector(1.2));
    const Vec tau = random.vector(3.0);
    const Vec sigma = random.vector(0.5).cwiseAbs() + Vec::Constant(0.05);
    const double F = 4.0 + trial;
    const auto est = tpf::estimate_contact_force<double, 4>(c.J, c.R, tau, sigma, F, settings);

    const Eigen::Matrix<double, 3, 4> Jc = c.R.transpose() * c.J.topRows<3>();
    const double sn = settings.prior_relative * F + settings.prior_floor_n;
    const double st = settings.shear_relative * F + settings.prior_floor_n;
    Eigen::Matrix<double, 7, 3> H = Eigen::Matrix<double, 7, 3>::Zero();
    Eigen::Matrix<double, 7, 1> y = Eigen::Matrix<double, 7, 1>::Zero();
    H.topRows<4>() = sigma.cwiseInverse().asDiagonal() * Jc.transpose();
    y.head<4>() = tau.cwiseQuotient(sigma);
    H(4, 0) = 1.0 / st;
    H(5, 1) = 1.0 / st;
    H(6, 2) = 1.0 / sn;
    y(6) = -F / sn;
    // The tiny shear ridge (1e-9 relative) is part of the solve; include it.
    const double ridge =
        settings.shear_regularisation * (H.topRows<4>().transpose() * H.topRows<4>()).trace();
    Eigen::Matrix<double, 9, 3> Hr = Eigen::Matrix<double, 9, 3>::Zero();
    Eigen::Matrix<double, 9, 1> yr = Eigen::Matrix<double, 9, 1>::Zero();
    Hr.topRows<7>() = H;
    yr.head<7>() = y;
    Hr(7, 0) = Hr(8, 1) = std::sqrt(ridge);
    const tpf::Vector3<double> f = Hr.colPivHouseholderQr().solve(yr);
    EXPECT_LT((est.force_contact - f).norm(), 1e-9 * (1.0 + f.norm())) << trial;
    const tpf::Matrix3<double> cov = (Hr.transpose() * Hr).inverse();
    EXPECT_LT((est.force_std_contact - cov.diagonal().cwiseSqrt()).norm(), 1e-9) << trial;
  }
}

// Without torque evidence (σ_τ = ∞ on every joint) the MAP is its prior: exactly the pad's
// answer (0, 0, −F_pad) with the prior's std, so fusion can never do worse than the pad when the
// torques are worthless and say so.
TEST(ContactForce, PriorAloneIsThePadAnswer) {
  const auto layout = pads();
  tpf::ContactForceSettings<double> settings;
  for (int k = 1; k < 11; ++k) {
    const Case c =
        pad_case(geometry(layout[static_cast<std::size_t>(k)]), Vec(0.3, -0.4, 0.7, 0.5));
    const Vec tau(1.0, -2.0, 0.5, 3.0);  // anything: it carries no weight
    const double F = 7.5;
    const auto est = tpf::estimate_contact_force<double, 4>(
        c.J, c.R, tau, Vec::Constant(std::numeric_limits<double>::infinity()), F, settings);
    EXPECT_LT((est.force_contact - tpf::Vector3<double>(0, 0, -F)).norm(), 1e-12) << k;
    const double st = settings.shear_relative * F + settings.prior_floor_n;
    const double sn = settings.prior_relative * F + settings.prior_floor_n;
    EXPECT_LT((est.force_std_contact - tpf::Vector3<double>(st, st, sn)).norm(), 1e-9) << k;
  }
}

// The two limits of the fusion: torques known far better than the pad → the arm decides (exact
// force, shear included); torques far worse → the pad decides (−F_pad along the normal).
TEST(ContactForce, WeighsTheTorquesAgainstThePadByTheirStd) {
  const auto layout = pads();
  const tpf::PadGeometry<double> pad = geometry(layout[9]);
  const Case c = pad_case(pad, Vec(0.3, -0.4, 0.7, 0.5));
  const tpf::Vector3<double> f_contact(3.0, -2.0, -10.0);
  const Vec tau = c.J.topRows<3>().transpose() * (c.R * f_contact);
  const double pad_reading = 6.0;  // the pad is off by 40 %
  const auto sharp =
      tpf::estimate_contact_force<double, 4>(c.J, c.R, tau, Vec::Constant(1e-4), pad_reading);
  ASSERT_TRUE(sharp.observable_by_arm);
  EXPECT_LT((sharp.force_contact - f_contact).norm(), 1e-3);
  const auto blunt =
      tpf::estimate_contact_force<double, 4>(c.J, c.R, tau, Vec::Constant(1e4), pad_reading);
  EXPECT_LT((blunt.force_contact - tpf::Vector3<double>(0, 0, -pad_reading)).norm(), 1e-3);
  EXPECT_NEAR(blunt.force_std_contact[2], 0.5 * pad_reading + 1.0, 1e-3);  // the prior's σ_n
  // One joint's torque badly wrong: declared by its σ, it no longer pulls the estimate away.
  Vec wrong = tau;
  wrong[1] += 5.0;
  const Vec equal = Vec::Constant(0.05);
  Vec declared = equal;
  declared[1] = 50.0;
  const auto naive = tpf::estimate_contact_force<double, 4>(c.J, c.R, wrong, equal, pad_reading);
  const auto aware = tpf::estimate_contact_force<double, 4>(c.J, c.R, wrong, declared, pad_reading);
  EXPECT_LT((aware.force_contact - f_contact).norm(),
            0.25 * (naive.force_contact - f_contact).norm());
}

}  // namespace
