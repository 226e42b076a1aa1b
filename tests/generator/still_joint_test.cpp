// A joint that never moves in the log (braked, or left out of the excitation): identify and
// diagnose fit the joints that move and keep every weight and value finite. The generator's
// two-link arm with its elbow held still at 0.5 rad.
#include <gtest/gtest.h>

#include <cmath>

#include "offline/diagnose/diagnose.hpp"
#include "offline/identify/identify.hpp"
#include "planar_arm_generator.hpp"
#include "tpf/model/load_robot.hpp"

namespace tpf::test {
namespace {

using offline::Regime;

offline::Log elbow_still_log(double elbow_amplitude) {
  PlanarArmPlant plant;
  plant.seed = 41;
  plant.duration_s = 40.0;
  plant.amplitude = {1.2, elbow_amplitude};
  return generate_planar_log(plant);
}

TEST(StillJoint, IdentifyFitsTheJointsThatMove) {
  const auto model = load_robot<double, Eigen::Dynamic>(planar_robot_file());
  const auto moving = offline::identify(elbow_still_log(1.4), model);
  const auto still = offline::identify(elbow_still_log(0.0), model);
  ASSERT_TRUE(still.joint_weights.allFinite()) << still.joint_weights.transpose();
  EXPECT_TRUE(still.nominal.base_values.allFinite());
  EXPECT_GT(still.nominal.base_values.norm(), 0.0);
  // The shoulder's held-out error as low as when both joints move (there: noise, quantisation
  // and friction memory); a fit that lost its weights predicts nothing (its gravity, ≈ 5 N·m).
  const double shoulder_moving = moving.heldout[0][Regime::Moving].rmse;
  const double shoulder_still = still.heldout[0][Regime::Moving].rmse;
  EXPECT_LT(shoulder_still, 1.5 * shoulder_moving) << shoulder_moving;
  // The elbow has no moving samples to score.
  EXPECT_EQ(still.heldout[1][Regime::Moving].count, 0);
}

TEST(StillJoint, DiagnoseFitsTheJointsThatMove) {
  const auto model = load_robot<double, Eigen::Dynamic>(planar_robot_file());
  const auto d = offline::diagnose(elbow_still_log(0.0), model);
  EXPECT_LT(d.before[0][2].rmse(), 0.2);
  EXPECT_TRUE(std::isfinite(d.after[0][2].rmse()));
}

}  // namespace
}  // namespace tpf::test
