// A mobile manipulator as a URDF tree, for the tests of prismatic joints and of chains cut from a
// tree: a base with a laser, a prismatic torso with a two-joint head (and a camera on it) and an
// IMU, then a 7-joint arm whose wrist carries a gripper with a sliding finger. The tree is a table
// of links (the source of both the URDF text and an independent reference: the tree's own forward
// kinematics, gravity torques and mass matrix, with every link of the tree as its own body).
#pragma once

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "tpf/common/types.hpp"

namespace tpf::test {

/// One link of the tree with the joint that attaches it to its parent (none for the root).
struct TreeLink {
  std::string name, parent, joint, type;  ///< type: fixed, revolute, continuous, prismatic
  std::array<double, 3> xyz{}, rpy{};     ///< the joint's origin in the parent's frame
  std::array<double, 3> axis{0, 0, 1};
  double mass = 0;
  std::array<double, 3> com{}, com_rpy{};
  std::array<double, 6> inertia{};  ///< ixx iyy izz ixy ixz iyz, in the inertial frame
};

/// The tree: root base_link; root_link base_link and tip_link wrist_3_link cut the chain
/// torso_lift (prismatic, z) + shoulder_pan … wrist_3 (7 revolute).
inline std::vector<TreeLink> mobile_arm_tree() {
  return {
      {"base_link",
       "",
       "",
       "",
       {},
       {},
       {},
       25.0,
       {0.0, 0.0, 0.15},
       {},
       {1.2, 1.4, 1.6, 0.0, 0.0, 0.0}},
      {"laser_link",
       "base_link",
       "laser_mount",
       "fixed",
       {0.25, 0.0, 0.2},
       {0.0, 0.0, 0.1},
       {},
       0.4,
       {0.0, 0.0, 0.02},
       {},
       {4e-4, 4e-4, 3e-4, 0.0, 0.0, 0.0}},
      {"torso_link",
       "base_link",
       "torso_lift",
       "prismatic",
       {-0.1, 0.02, 0.35},
       {0.0, 0.0, 0.05},
       {0, 0, 1},
       9.0,
       {0.03, 0.0, 0.3},
       {0.0, 0.1, 0.0},
       {0.35, 0.33, 0.05, 0.01, -0.02, 0.005}},
      {"imu_link",
       "torso_link",
       "imu_mount",
       "fixed",
       {0.0, 0.1, 0.2},
       {0.3, 0.0, 0.0},
       {},
       0.15,
       {0.01, 0.0, 0.0},
       {},
       {1e-4, 2e-4, 1.5e-4, 0.0, 0.0, 0.0}},
      {"head_pan_link",
       "torso_link",
       "head_pan",
       "revolute",
       {0.05, 0.0, 0.65},
       {0.0, 0.0, 0.2},
       {0, 0, 1},
       1.1,
       {0.02, 0.01, 0.04},
       {0.1, 0.2, 0.3},
       {3e-3, 2.5e-3, 2e-3, 1e-4, 0.0, -2e-4}},
      {"head_tilt_link",
       "head_pan_link",
       "head_tilt",
       "revolute",
       {0.03, 0.0, 0.08},
       {0.1, 0.0, 0.0},
       {0, 1, 0},
       0.9,
       {0.05, -0.01, 0.02},
       {0.0, 0.4, 0.0},
       {2e-3, 1.8e-3, 2.2e-3, 0.0, 1e-4, 0.0}},
      {"camera_link",
       "head_tilt_link",
       "camera_mount",
       "fixed",
       {0.09, 0.0, 0.03},
       {-0.2, 0.1, 0.0},
       {},
       0.35,
       {0.0, 0.02, 0.0},
       {0.3, 0.0, 0.2},
       {5e-4, 3e-4, 4e-4, 0.0, 0.0, 5e-5}},
      {"shoulder_pan_link",
       "torso_link",
       "shoulder_pan",
       "revolute",
       {0.12, 0.0, 0.45},
       {0.0, 0.0, 0.0},
       {0, 0, 1},
       2.3,
       {0.05, 0.0, 0.02},
       {},
       {6e-3, 8e-3, 7e-3, 0.0, 1e-3, 0.0}},
      {"shoulder_lift_link",
       "shoulder_pan_link",
       "shoulder_lift",
       "revolute",
       {0.12, 0.0, 0.06},
       {0.0, 0.0, 0.0},
       {0, 1, 0},
       2.1,
       {0.14, 0.0, 0.0},
       {},
       {4e-3, 1.2e-2, 1.1e-2, 0.0, 0.0, 0.0}},
      {"upperarm_roll_link",
       "shoulder_lift_link",
       "upperarm_roll",
       "continuous",
       {0.22, 0.0, 0.0},
       {0.0, 0.0, 0.0},
       {1, 0, 0},
       1.8,
       {0.1, 0.01, 0.0},
       {},
       {3e-3, 9e-3, 9e-3, 0.0, 0.0, 0.0}},
      {"elbow_flex_link",
       "upperarm_roll_link",
       "elbow_flex",
       "revolute",
       {0.13, 0.0, 0.0},
       {0.0, 0.0, 0.3},
       {0, 1, 0},
       1.6,
       {0.12, 0.0, 0.01},
       {0.0, 0.0, 0.2},
       {2.5e-3, 8e-3, 7.5e-3, 0.0, 2e-4, 0.0}},
      {"forearm_roll_link",
       "elbow_flex_link",
       "forearm_roll",
       "continuous",
       {0.2, 0.0, 0.0},
       {0.0, 0.0, 0.0},
       {1, 0, 0},
       1.3,
       {0.09, 0.0, 0.0},
       {},
       {2e-3, 5e-3, 5e-3, 0.0, 0.0, 0.0}},
      {"wrist_flex_link",
       "forearm_roll_link",
       "wrist_flex",
       "revolute",
       {0.14, 0.0, 0.0},
       {0.0, -0.1, 0.0},
       {0, 1, 0},
       0.9,
       {0.07, 0.0, 0.0},
       {},
       {1e-3, 2e-3, 2e-3, 0.0, 0.0, 0.0}},
      {"wrist_3_link",
       "wrist_flex_link",
       "wrist_roll",
       "continuous",
       {0.14, 0.0, 0.0},
       {0.0, 0.0, 0.0},
       {1, 0, 0},
       0.6,
       {0.03, 0.0, 0.0},
       {},
       {6e-4, 8e-4, 8e-4, 0.0, 0.0, 0.0}},
      {"gripper_link",
       "wrist_3_link",
       "gripper_mount",
       "fixed",
       {0.08, 0.0, 0.0},
       {0.2, 0.0, 0.0},
       {},
       0.7,
       {0.05, 0.0, 0.0},
       {},
       {1e-3, 1.5e-3, 1.4e-3, 0.0, 0.0, 0.0}},
      {"finger_link",
       "gripper_link",
       "finger_slide",
       "prismatic",
       {0.1, 0.02, 0.0},
       {0.0, 0.0, 0.0},
       {0, 1, 0},
       0.1,
       {0.02, 0.0, 0.0},
       {},
       {2e-5, 2e-5, 2e-5, 0.0, 0.0, 0.0}},
  };
}

/// The URDF text of a tree table.
inline std::string tree_urdf(const std::vector<TreeLink>& tree) {
  std::ostringstream s;
  s.precision(17);
  const auto triple = [&](const std::array<double, 3>& v) {
    std::ostringstream t;
    t.precision(17);
    t << v[0] << " " << v[1] << " " << v[2];
    return t.str();
  };
  s << "<?xml version=\"1.0\"?>\n<robot name=\"mobile_arm\">\n";
  for (const TreeLink& l : tree) {
    s << "  <link name=\"" << l.name << "\"><inertial><origin xyz=\"" << triple(l.com)
      << "\" rpy=\"" << triple(l.com_rpy) << "\"/><mass value=\"" << l.mass << "\"/><inertia ixx=\""
      << l.inertia[0] << "\" iyy=\"" << l.inertia[1] << "\" izz=\"" << l.inertia[2] << "\" ixy=\""
      << l.inertia[3] << "\" ixz=\"" << l.inertia[4] << "\" iyz=\"" << l.inertia[5]
      << "\"/></inertial></link>\n";
  }
  for (const TreeLink& l : tree) {
    if (l.parent.empty()) continue;
    s << "  <joint name=\"" << l.joint << "\" type=\"" << l.type << "\"><parent link=\"" << l.parent
      << "\"/><child link=\"" << l.name << "\"/><origin xyz=\"" << triple(l.xyz) << "\" rpy=\""
      << triple(l.rpy) << "\"/>";
    if (l.type != "fixed") s << "<axis xyz=\"" << triple(l.axis) << "\"/>";
    if (l.type == "prismatic")
      s << "<limit lower=\"0\" upper=\"0.4\" effort=\"800\" velocity=\"0.1\"/>";
    else if (l.type == "revolute")
      s << "<limit lower=\"-2.5\" upper=\"2.5\" effort=\"60\" velocity=\"2\"/>";
    s << "</joint>\n";
  }
  s << "</robot>\n";
  return s.str();
}

/// The joints of the chain base_link → wrist_3_link, in order.
inline std::vector<std::string> mobile_arm_chain_joints() {
  return {"torso_lift", "shoulder_pan", "shoulder_lift", "upperarm_roll",
          "elbow_flex", "forearm_roll", "wrist_flex",    "wrist_roll"};
}

/// Writes the URDF and a robot file (root_link base_link, tip_link wrist_3_link, a drive per chain
/// joint: the torso's a ball screw) into `folder`; returns the robot file.
inline std::filesystem::path write_mobile_arm(const std::filesystem::path& folder,
                                              const std::string& ends =
                                                  "\"root_link\": "
                                                  "\"base_link\", "
                                                  "\"tip_link\": "
                                                  "\"wrist_3_link\",") {
  std::filesystem::create_directories(folder);
  std::ofstream(folder / "mobile_arm.urdf") << tree_urdf(mobile_arm_tree());
  std::ostringstream j;
  j.precision(17);
  j << "{\"format\": \"tpf-robot\", \"version\": 1, \"name\": \"mobile_arm\", \"urdf\": "
       "\"mobile_arm.urdf\", "
    << ends << " \"joints\": [";
  const std::vector<std::string> joints = mobile_arm_chain_joints();
  for (std::size_t k = 0; k < joints.size(); ++k) {
    // The torso: a 5 mm lead ball screw behind a 10:1 gearbox, 2π·10/0.005 rad/m.
    const bool torso = k == 0;
    j << (k ? ", " : "") << "{\"name\": \"" << joints[k]
      << "\", \"gear_ratio\": " << (torso ? 2 * M_PI * 10 / 0.005 : 100.0)
      << ", \"rotor_inertia\": " << (torso ? 2e-6 : 1e-5)
      << ", \"torque_constant\": " << (torso ? 3000.0 : 10.0) << ", \"current_limit\": 5000}";
  }
  j << "]}";
  std::ofstream(folder / "mobile_arm.robot.json") << j.str();
  return folder / "mobile_arm.robot.json";
}

/// URDF's rpy: R = Rz(yaw)·Ry(pitch)·Rx(roll).
inline Matrix3<double> rpy_rotation(const std::array<double, 3>& rpy) {
  return (Eigen::AngleAxisd(rpy[2], Vector3<double>::UnitZ()) *
          Eigen::AngleAxisd(rpy[1], Vector3<double>::UnitY()) *
          Eigen::AngleAxisd(rpy[0], Vector3<double>::UnitX()))
      .toRotationMatrix();
}

/// The tree's own forward kinematics at chain positions `q` (by joint name; every other movable
/// joint at 0), the root at the world origin: each link's world pose, and each joint's world
/// origin and axis.
struct TreePose {
  std::map<std::string, Transform<double>> link;        ///< by link name
  std::map<std::string, Vector3<double>> joint_origin;  ///< by joint name
  std::map<std::string, Vector3<double>> joint_axis;

  TreePose(const std::vector<TreeLink>& tree, const std::map<std::string, double>& q) {
    for (const TreeLink& l : tree) {  // parents come before their children in the table
      if (l.parent.empty()) {
        link[l.name] = Transform<double>{};
        continue;
      }
      const Transform<double>& parent = link.at(l.parent);
      Transform<double> joint;
      joint.R = parent.R * rpy_rotation(l.rpy);
      joint.p = parent.p + parent.R * Vector3<double>(l.xyz[0], l.xyz[1], l.xyz[2]);
      const Vector3<double> axis = Vector3<double>(l.axis[0], l.axis[1], l.axis[2]).normalized();
      const double position = q.contains(l.joint) ? q.at(l.joint) : 0.0;
      joint_origin[l.joint] = joint.p;
      joint_axis[l.joint] = joint.R * axis;
      Transform<double> child = joint;
      if (l.type == "prismatic")
        child.p += position * (joint.R * axis);
      else if (l.type != "fixed")
        child.R = joint.R * Eigen::AngleAxisd(position, axis).toRotationMatrix();
      link[l.name] = child;
    }
  }
};

/// Whether `link` is `ancestor` or lies below it in the tree.
inline bool at_or_below(const std::vector<TreeLink>& tree, std::string link,
                        const std::string& ancestor) {
  while (!link.empty()) {
    if (link == ancestor) return true;
    for (const TreeLink& l : tree)
      if (l.name == link) {
        link = l.parent;
        break;
      }
  }
  return false;
}

/// A link's world centre of mass and rotational inertia about it (world axes).
inline void world_inertia(const TreeLink& l, const TreePose& pose, Vector3<double>& c,
                          Matrix3<double>& I) {
  const Transform<double>& T = pose.link.at(l.name);
  c = T.apply(Vector3<double>(l.com[0], l.com[1], l.com[2]));
  Matrix3<double> local;
  local << l.inertia[0], l.inertia[3], l.inertia[4], l.inertia[3], l.inertia[1], l.inertia[5],
      l.inertia[4], l.inertia[5], l.inertia[2];
  const Matrix3<double> R = T.R * rpy_rotation(l.com_rpy);
  I = R * local * R.transpose();
}

/// The chain joints' Jacobian (6 × n, [linear; angular], world) of the centre of mass of tree
/// link `l`: column j is zero unless chain joint j moves the link.
inline Eigen::MatrixXd tree_com_jacobian(const std::vector<TreeLink>& tree, const TreeLink& l,
                                         const TreePose& pose,
                                         const std::vector<std::string>& chain) {
  Vector3<double> c;
  Matrix3<double> I;
  world_inertia(l, pose, c, I);
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(6, static_cast<Eigen::Index>(chain.size()));
  for (std::size_t j = 0; j < chain.size(); ++j) {
    const auto it = std::find_if(tree.begin(), tree.end(),
                                 [&](const TreeLink& t) { return t.joint == chain[j]; });
    if (!at_or_below(tree, l.name, it->name)) continue;
    const Vector3<double>& z = pose.joint_axis.at(chain[j]);
    const auto col = static_cast<Eigen::Index>(j);
    if (it->type == "prismatic") {
      J.block<3, 1>(0, col) = z;
    } else {
      J.block<3, 1>(0, col) = z.cross(c - pose.joint_origin.at(chain[j]));
      J.block<3, 1>(3, col) = z;
    }
  }
  return J;
}

/// The tree's gravity efforts at the chain joints: G = −Σ_links J_v,linkᵀ m g (every link a body
/// of its own, none folded).
inline Eigen::VectorXd tree_gravity(const std::vector<TreeLink>& tree, const TreePose& pose,
                                    const std::vector<std::string>& chain,
                                    const Vector3<double>& gravity) {
  Eigen::VectorXd G = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(chain.size()));
  for (const TreeLink& l : tree)
    G -= tree_com_jacobian(tree, l, pose, chain).topRows<3>().transpose() * (l.mass * gravity);
  return G;
}

/// The tree's mass matrix at the chain joints, without armature: Σ_links J_vᵀ m J_v + J_ωᵀ I J_ω.
inline Eigen::MatrixXd tree_mass_matrix(const std::vector<TreeLink>& tree, const TreePose& pose,
                                        const std::vector<std::string>& chain) {
  const auto n = static_cast<Eigen::Index>(chain.size());
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(n, n);
  for (const TreeLink& l : tree) {
    Vector3<double> c;
    Matrix3<double> I;
    world_inertia(l, pose, c, I);
    const Eigen::MatrixXd J = tree_com_jacobian(tree, l, pose, chain);
    M += l.mass * J.topRows<3>().transpose() * J.topRows<3>() +
         J.bottomRows<3>().transpose() * I * J.bottomRows<3>();
  }
  return M;
}

}  // namespace tpf::test
