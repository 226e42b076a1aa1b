// A random serial arm of any joint count, for tests of the run-time-size code on arms the
// project's robot files do not cover (8, 9, 12 joints), as a model and as a robot description.
#pragma once

#include <cmath>
#include <random>
#include <string>

#include "tpf/model/model.hpp"
#include "tpf/model/robot_description.hpp"

namespace tpf::test {

/// A random serial arm of n revolute joints: placements up to 0.3 m and any rotation, random unit
/// axes (some along a coordinate axis, the kinematics' shortcut), random positive definite link
/// inertias, armature. Seeded.
inline Model<double, Eigen::Dynamic> random_arm(int n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  auto vector3 = [&] { return Vector3<double>(u(rng), u(rng), u(rng)); };
  Model<double, Eigen::Dynamic> model;
  model.resize(n);
  model.name = std::string("random").append(std::to_string(n));
  for (int k = 0; k < n; ++k) {
    model.joint_names[k] = std::string("j").append(std::to_string(k + 1));
    model.link_names[k + 1] = std::string("l").append(std::to_string(k + 1));
    const Eigen::Quaterniond rotation = Eigen::Quaterniond::UnitRandom();
    model.joint_placements[k] = {rotation.toRotationMatrix(), 0.3 * vector3()};
    model.axes[k] = k % 3 == 0 ? Vector3<double>::Unit(k % 2 == 0 ? 2 : 1) : vector3().normalized();
    Inertia<double>& body = model.inertias[k + 1];
    body.mass = 0.5 + std::abs(u(rng)) * 3.0;
    body.com = 0.1 * vector3();
    const Matrix3<double> A = 0.05 * Matrix3<double>::Random();
    body.rotational = A * A.transpose() + 0.01 * Matrix3<double>::Identity();
    model.armature(k) = 0.1 * std::abs(u(rng));
  }
  model.link_names[0] = "base";
  model.update_constants();
  return model;
}

/// The robot description of `model` (chain, drives with gear ratio 100 and the model's armature,
/// joint limits ±3 rad), as load_robot_description would give for its files.
inline RobotDescription robot_description_of(const Model<double, Eigen::Dynamic>& model) {
  RobotDescription d;
  d.source = model.name + ".robot.json";
  d.chain.source = model.name + ".urdf";
  d.chain.robot_name = model.name;
  d.chain.base_link = model.link_names[0];
  d.chain.inertias.push_back(model.inertias[0]);
  for (int k = 0; k < model.joint_count(); ++k) {
    ChainJoint joint;
    joint.name = model.joint_names[k];
    joint.child_link = model.link_names[k + 1];
    joint.placement = model.joint_placements[k];
    joint.axis = model.axes[k];
    joint.lower = -3.0;
    joint.upper = 3.0;
    d.chain.joints.push_back(joint);
    d.chain.inertias.push_back(model.inertias[k + 1]);
    DriveDescription drive;
    drive.joint = joint.name;
    drive.gear_ratio = 100.0;
    drive.rotor_inertia = model.armature(k) / (100.0 * 100.0);
    drive.torque_constant = 1.0;
    d.drives.push_back(drive);
  }
  d.gravity = model.gravity;
  return d;
}

}  // namespace tpf::test
