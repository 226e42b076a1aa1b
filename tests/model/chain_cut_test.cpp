// A chain cut from a branching URDF by the robot file's root_link and tip_link: the mobile arm's
// tree (support/mobile_arm.hpp) with its head, sensors and gripper folded into the chain links as
// fixed mass, checked against the tree's own gravity torques and mass matrix (every link a body of
// its own); and the messages for a tree without ends, or with ends that are no chain.
#include <gtest/gtest.h>

#include <random>

#include "support/arm_fixture.hpp"
#include "support/mobile_arm.hpp"
#include "support/temp_dir.hpp"

namespace tpf::test {
namespace {

namespace fs = std::filesystem;

const TempDir kTree("chain_cut_tests");

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

/// Random chain positions: the torso within its travel, the rest within ±2 rad.
std::map<std::string, double> random_positions(std::mt19937_64& rng, Eigen::VectorXd& q) {
  const std::vector<std::string> chain = mobile_arm_chain_joints();
  std::uniform_real_distribution<double> torso(0.0, 0.4), angle(-2.0, 2.0);
  q.resize(static_cast<Eigen::Index>(chain.size()));
  std::map<std::string, double> by_name;
  for (std::size_t k = 0; k < chain.size(); ++k) {
    q(static_cast<Eigen::Index>(k)) = k == 0 ? torso(rng) : angle(rng);
    by_name[chain[k]] = q(static_cast<Eigen::Index>(k));
  }
  return by_name;
}

TEST(ChainCut, RootAndTipGiveThePathWithAPrismaticTorso) {
  const RobotDescription robot = load_robot_description(write_mobile_arm(kTree / "arm"));
  EXPECT_EQ(robot.chain.base_link, "base_link");
  EXPECT_EQ(robot.chain.tip_link, "wrist_3_link");
  const std::vector<std::string> names = mobile_arm_chain_joints();
  ASSERT_EQ(robot.chain.joints.size(), names.size());
  for (std::size_t k = 0; k < names.size(); ++k) {
    EXPECT_EQ(robot.chain.joints[k].name, names[k]);
    EXPECT_EQ(robot.chain.joints[k].type, k == 0 ? JointType::prismatic : JointType::revolute);
  }
  EXPECT_EQ(robot.chain.joints[0].lower, 0.0);
  EXPECT_EQ(robot.chain.joints[0].upper, 0.4);
  const auto model = make_model<double, Eigen::Dynamic>(robot);
  EXPECT_TRUE(model.is_prismatic(0));
  // The torso's drive: armature = rotor inertia × (rad/m)², a reflected mass in kg.
  EXPECT_NEAR(model.armature(0), 2e-6 * std::pow(2 * M_PI * 10 / 0.005, 2), 1e-9);
  // link 1 (the torso) carries the IMU and the head: 9 + 0.15 + 1.1 + 0.9 + 0.35 kg; the wrist
  // carries the gripper and its finger: 0.6 + 0.7 + 0.1 kg.
  EXPECT_NEAR(model.inertias[1].mass, 11.5, 1e-12);
  EXPECT_NEAR(model.inertias[8].mass, 1.4, 1e-12);
  // the base and its laser are the world: no joint moves them
  EXPECT_NEAR(model.inertias[0].mass, 25.4, 1e-12);
}

TEST(ChainCut, FoldedBranchesGiveTheTreesGravityTorquesAndMassMatrix) {
  const fs::path file = write_mobile_arm(kTree / "arm");
  const auto model = load_robot<double, Eigen::Dynamic>(file);
  Data<double, Eigen::Dynamic> data(model);
  const std::vector<TreeLink> tree = mobile_arm_tree();
  const std::vector<std::string> chain = mobile_arm_chain_joints();
  std::mt19937_64 rng(17);
  for (int trial = 0; trial < 20; ++trial) {
    Eigen::VectorXd q;
    const TreePose pose(tree, random_positions(rng, q));
    const Eigen::VectorXd G_tree = tree_gravity(tree, pose, chain, model.gravity);
    const Eigen::VectorXd G = compute_gravity(model, data, q);
    EXPECT_LT((G - G_tree).cwiseAbs().maxCoeff(), 1e-10 * G_tree.norm()) << "trial " << trial;
    // The torso lifts everything but the base and the laser.
    EXPECT_NEAR(G(0), 9.81 * (11.5 + 2.3 + 2.1 + 1.8 + 1.6 + 1.3 + 0.9 + 1.4), 1e-9);
    const Eigen::MatrixXd M_tree = tree_mass_matrix(tree, pose, chain);
    const Eigen::MatrixXd M = compute_mass_matrix(model, data, q);
    const Eigen::MatrixXd armature = model.armature.asDiagonal();
    EXPECT_LT((M - armature - M_tree).cwiseAbs().maxCoeff(), 1e-10 * M_tree.norm())
        << "trial " << trial;
    // The chain's link poses are the tree's.
    forward_kinematics(model, data, q);
    for (int k = 1; k <= 8; ++k) {
      const Transform<double>& T = pose.link.at(model.link_names[k]);
      EXPECT_LT((data.oMi[k].p - T.p).norm(), 1e-12) << model.link_names[k];
      EXPECT_LT((data.oMi[k].R - T.R).norm(), 1e-12) << model.link_names[k];
    }
  }
}

TEST(ChainCut, ARootAloneTakesTheSerialChainBelowIt) {
  // Below the shoulder the tree is serial: six revolute joints, then the finger's slide.
  std::ofstream(kTree / "tree.urdf") << tree_urdf(mobile_arm_tree());
  const ChainDescription chain =
      load_urdf_chain(kTree / "tree.urdf", {"shoulder_pan_link", "", "robot.json"});
  ASSERT_EQ(chain.joints.size(), 7u);
  EXPECT_EQ(chain.base_link, "shoulder_pan_link");
  EXPECT_EQ(chain.tip_link, "finger_link");
  EXPECT_EQ(chain.joints[0].name, "shoulder_lift");
  EXPECT_EQ(chain.joints[6].name, "finger_slide");
  EXPECT_EQ(chain.joints[6].type, JointType::prismatic);
}

TEST(ChainCut, ATreeWithoutEndsIsRefusedAtTheLinkWhereItBranches) {
  const fs::path file = write_mobile_arm(kTree / "no_ends", "");
  const std::string message = error_of([&] { load_robot_description(file); });
  EXPECT_NE(message.find("mobile_arm.urdf"), std::string::npos) << message;
  EXPECT_NE(message.find("link 'torso_link'"), std::string::npos) << message;
  EXPECT_NE(message.find("branches"), std::string::npos) << message;
  EXPECT_NE(message.find("\"root_link\" and \"tip_link\""), std::string::npos) << message;
  // the URDF alone, as the tools read it
  EXPECT_EQ(error_of([&] { load_urdf_chain(kTree / "no_ends" / "mobile_arm.urdf"); }), message);
}

TEST(ChainCut, EndsThatAreNoChainAreRefusedNamingTheLinkAndTheRobotFile) {
  const auto ends = [](const std::string& root, const std::string& tip) {
    return "\"root_link\": \"" + root + "\", \"tip_link\": \"" + tip + "\",";
  };
  const fs::path unknown = write_mobile_arm(kTree / "unknown", ends("base_link", "hand"));
  std::string message = error_of([&] { load_robot_description(unknown); });
  EXPECT_NE(message.find("mobile_arm.urdf"), std::string::npos) << message;
  EXPECT_NE(message.find("no link 'hand'"), std::string::npos) << message;
  EXPECT_NE(message.find("tip_link of"), std::string::npos) << message;
  EXPECT_NE(message.find(unknown.string()), std::string::npos) << message;

  const fs::path apart = write_mobile_arm(kTree / "apart", ends("head_pan_link", "wrist_3_link"));
  message = error_of([&] { load_robot_description(apart); });
  EXPECT_NE(message.find("link 'wrist_3_link'"), std::string::npos) << message;
  EXPECT_NE(message.find("does not lie below root_link 'head_pan_link'"), std::string::npos)
      << message;

  const fs::path same = write_mobile_arm(kTree / "same", ends("torso_link", "torso_link"));
  message = error_of([&] { load_robot_description(same); });
  EXPECT_NE(message.find("both root_link and tip_link"), std::string::npos) << message;

  // A chain that ends at the torso: one prismatic joint, but the robot file lists eight.
  const fs::path short_chain = write_mobile_arm(kTree / "short", ends("base_link", "torso_link"));
  message = error_of([&] { load_robot_description(short_chain); });
  EXPECT_NE(message.find("must list the 1 joints"), std::string::npos) << message;
}

TEST(ChainCut, APrismaticJointWithoutTravelIsRefused) {
  std::vector<TreeLink> tree = mobile_arm_tree();
  std::string urdf = tree_urdf(tree);
  const std::string limit = "<limit lower=\"0\" upper=\"0.4\" effort=\"800\" velocity=\"0.1\"/>";
  urdf.replace(urdf.find(limit), limit.size(), "<limit effort=\"800\" velocity=\"0.1\"/>");
  std::ofstream(kTree / "travel.urdf") << urdf;
  const std::string message = error_of([&] {
    load_urdf_chain(kTree / "travel.urdf", {"base_link", "wrist_3_link", ""});
  });
  EXPECT_NE(message.find("joint 'torso_lift'"), std::string::npos) << message;
  EXPECT_NE(message.find("in m"), std::string::npos) << message;
}

}  // namespace
}  // namespace tpf::test
