// Issue 16, requirement 4: identify's friction curve is at least as good in held-out RMS as a
// linear Coulomb + viscous fit (plain least squares, unconstrained) of the same friction target
// on the same samples, on every test log: the generator's logs (friction with memory, noise,
// quantisation, random stops; each trap planted) and the measured Kinova Gen3 logs.
// Where that fit needs a negative coefficient (Kinova joint 3: τ_c 1.78, b −1.15 N·m·s/rad), the
// curve is held to the best dissipative linear fit and identify must say why it loses to the plain
// one.
#include <gtest/gtest.h>

#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "support/kinova_logs.hpp"
#include "offline/identify/identification_setup.hpp"
#include "offline/identify/identify.hpp"
#include "offline/log/read_logs.hpp"
#include "planar_arm_generator.hpp"
#include "tpf/friction/stribeck.hpp"
#include "tpf/model/load_robot.hpp"

namespace tpf::test {
namespace {

using offline::Regime;

struct HeldOutRms {
  double curve = 0, linear = 0;
  double dissipative = 0;  ///< the linear fit with τ_c, b ≥ 0 (= linear where both come out ≥ 0)
  bool negative = false;  ///< the plain least-squares fit has τ_c < 0 or b < 0
  Eigen::Index samples = 0;
};

// Per joint: held-out RMS of the friction target effort − rigid prediction (= identify's residual
// + its written friction) against the written curve and against c·sgn(q̇) + b·q̇ fitted by least
// squares on the training samples; non-static samples, as identify fits and compares them.
std::vector<HeldOutRms> curve_against_linear(const offline::Identification& id,
                                             const Model<double, Eigen::Dynamic>& model) {
  const offline::JointSamples& s = id.samples;
  const Eigen::MatrixXd load = offline::gravity_load(model, s);
  const int joints = model.joint_count();
  std::vector<HeldOutRms> out(static_cast<std::size_t>(joints));
  for (int j = 0; j < joints; ++j) {
    std::vector<Eigen::Index> training, heldout;
    for (Eigen::Index k = 0; k < s.size(); ++k)
      if (s.valid[k] && s.regimes[j][k] != Regime::Static && s.regimes[j][k] != Regime::Invalid &&
          std::isfinite(id.residual(k, j)))
        (s.heldout[k] ? heldout : training).push_back(k);
    if (training.size() < 50 || heldout.empty()) continue;
    auto written = [&](Eigen::Index k) {
      const Eigen::VectorXd dq = s.dq.row(k).transpose(), g = load.row(k).transpose();
      return stribeck_friction(id.nominal.friction, dq, g)[j];
    };
    auto target = [&](Eigen::Index k) { return id.residual(k, j) + written(k); };
    auto sgn = [](double v) { return v > 0 ? 1.0 : (v < 0 ? -1.0 : 0.0); };
    Eigen::MatrixXd a(static_cast<Eigen::Index>(training.size()), 2);
    Eigen::VectorXd b(a.rows());
    for (Eigen::Index i = 0; i < a.rows(); ++i) {
      const Eigen::Index k = training[static_cast<std::size_t>(i)];
      a(i, 0) = sgn(s.dq(k, j));
      a(i, 1) = s.dq(k, j);
      b[i] = target(k);
    }
    const Eigen::Vector2d linear = a.colPivHouseholderQr().solve(b);
    // With a negative coefficient, the non-negative optimum keeps one column (the better one).
    Eigen::Vector2d dissipative = linear;
    if ((linear.array() < 0).any()) {
      double best = std::numeric_limits<double>::infinity();
      for (int c = 0; c < 2; ++c) {
        Eigen::Vector2d x = Eigen::Vector2d::Zero();
        x[c] = std::max(a.col(c).dot(b) / a.col(c).squaredNorm(), 0.0);
        const double sse = (b - a * x).squaredNorm();
        if (sse < best) best = sse, dissipative = x;
      }
    }
    auto heldout_rms = [&](const Eigen::Vector2d& x) {
      double sse = 0;
      for (Eigen::Index k : heldout)
        sse += std::pow(target(k) - x[0] * sgn(s.dq(k, j)) - x[1] * s.dq(k, j), 2);
      return std::sqrt(sse / static_cast<double>(heldout.size()));
    };
    double sse_curve = 0;
    for (Eigen::Index k : heldout)
      sse_curve += std::pow(id.residual(k, j), 2);
    out[j] = {std::sqrt(sse_curve / static_cast<double>(heldout.size())), heldout_rms(linear),
              heldout_rms(dissipative), (linear.array() < 0).any(),
              static_cast<Eigen::Index>(heldout.size())};
  }
  return out;
}

void expect_curve_no_worse(const offline::Log& log, const Model<double, Eigen::Dynamic>& model,
                           const std::string& label) {
  const offline::Identification id = offline::identify(log, model);
  const auto rms = curve_against_linear(id, model);
  for (const std::string& note : id.friction_notes)
    std::printf("  [%s] %s\n", label.c_str(), note.c_str());
  int compared = 0;
  for (int j = 0; j < model.joint_count(); ++j) {
    if (rms[j].samples == 0) continue;
    ++compared;
    std::printf(
        "  [%s] joint %d: held-out friction RMS, written curve %.4f, linear %.4f N·m (%ld "
        "samples)\n",
        label.c_str(), j + 1, rms[j].curve, rms[j].linear, static_cast<long>(rms[j].samples));
    // "At least as good": 0.5 % of slack for the linear fit's own noise on the held-out blocks.
    // Where plain least squares needs a negative coefficient, no dissipative friction can follow
    // it: the curve must then beat the dissipative linear fit, and identify must say why it
    // loses to the plain one.
    EXPECT_LE(rms[j].curve, 1.005 * rms[j].dissipative) << label << ", joint " << j + 1;
    const std::string prefix = "joint " + std::to_string(j + 1) + ": plain least squares";
    const bool said = std::any_of(id.friction_notes.begin(), id.friction_notes.end(),
                                  [&](const std::string& n) { return n.rfind(prefix, 0) == 0; });
    if (rms[j].curve > 1.005 * rms[j].linear) {
      EXPECT_TRUE(rms[j].negative) << label << ", joint " << j + 1;
      EXPECT_TRUE(said) << label << ", joint " << j + 1 << ": the loss to plain least squares";
    }
  }
  EXPECT_GT(compared, 0) << label;
}

TEST(IdentifyFriction, CurveIsNoWorseThanLinearOnTheGeneratorsLogs) {
  const auto model = load_robot<double, Eigen::Dynamic>(planar_robot_file());
  struct Case {
    const char* label;
    PlanarArmPlant plant;
  };
  std::vector<Case> cases(6);
  cases[0].label = "clean";
  cases[0].plant.seed = 11;
  cases[1].label = "offset, short range";
  cases[1].plant.seed = 21;
  cases[1].plant.amplitude = {1.2, 0.2};
  cases[1].plant.offset = {0.0, 0.3};
  cases[2].label = "asymmetric Coulomb";
  cases[2].plant.seed = 22;
  cases[2].plant.coulomb_positive = {0.60, 0.25};
  cases[2].plant.coulomb_negative = {0.25, 0.25};
  cases[3].label = "delay 20 ms";
  cases[3].plant.seed = 23;
  cases[3].plant.delay_s = 0.02;
  cases[4].label = "neighbour-load friction";
  cases[4].plant.seed = 24;
  cases[4].plant.neighbour_load = 0.25;
  cases[5].label = "no stops, strong viscous";
  cases[5].plant.seed = 27;
  cases[5].plant.random_stops = false;
  cases[5].plant.viscous = {0.8, 0.5};
  for (const Case& c : cases)
    expect_curve_no_worse(generate_planar_log(c.plant), model, c.label);
}

TEST(IdentifyFriction, CurveIsNoWorseThanLinearOnTheKinovaLogs) {
  const auto model = joint_count_cast<Eigen::Dynamic>(kinova_model());
  expect_curve_no_worse(offline::read_logs(kinova_fitting_files()), model, "Kinova fitting files");
  expect_curve_no_worse(offline::read_logs(kinova_testing_files()), model, "Kinova testing files");
}

// The Gen3's joint 1 turns about the vertical: its gravity torque is zero up to rounding, so a
// load column α·|G| there could only fit noise (it gave α_v ≈ 2.5e3). Held at zero and said; the
// joints that carry gravity keep theirs.
TEST(IdentifyFriction, NoLoadFrictionOnAVerticalAxis) {
  const offline::Identification id = offline::identify(
      offline::read_logs(kinova_fitting_files()), joint_count_cast<Eigen::Dynamic>(kinova_model()));
  const auto& f = id.nominal.friction;
  EXPECT_EQ(f.load_coulomb[0], 0.0);
  EXPECT_EQ(f.load_viscous[0], 0.0);
  EXPECT_GT(f.load_coulomb.tail(6).sum() + f.load_viscous.tail(6).sum(), 0.0);
  std::vector<std::string> said;
  for (const std::string& note : id.friction_notes)
    if (note.find("its gravity torque stays below") != std::string::npos) said.push_back(note);
  ASSERT_EQ(said.size(), 1u);
  EXPECT_EQ(said[0].rfind("joint 1: ", 0), 0u) << said[0];
}

}  // namespace
}  // namespace tpf::test
