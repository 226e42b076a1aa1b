// The contact force from joint torques: exact recovery where the arm observes it, the pad prior
// where it does not, and an honest validity flag where neither does.
#include "tpf/estimation/contact_force.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "support/arm_fixture.hpp"
#include "tpf/kinematics/point_jacobian.hpp"
#include "tpf/skin/skin.hpp"

namespace {

using tpf::test::arm;
using tpf::test::Vec;

double angle_deg(const tpf::Vector3<double>& a, const tpf::Vector3<double>& b) {
  return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)) * 180.0 / M_PI;
}

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
    const auto est = tpf::estimate_contact_force<double, 4>(c.J, c.R, tau, 10.0);
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
  const auto est = tpf::estimate_contact_force<double, 4>(c.J, c.R, tau, 12.0);
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

}  // namespace
