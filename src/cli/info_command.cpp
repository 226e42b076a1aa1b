// `tpf info`: load a robot and print its model and a few computed quantities.
#include <algorithm>
#include <cstdio>
#include <iostream>
#include <string>

#include "commands.hpp"
#include "model_file_options.hpp"
#include "offline/common/data_files.hpp"
#include "offline/common/run_time_types.hpp"
#include "core/common/unoptimised_when_sanitized.hpp"
#include "option_validators.hpp"
#include "tpf/core.hpp"

TPF_UNOPTIMISED_WHEN_SANITIZED_BEGIN

namespace tpf::cli {

namespace {

/// A pose that loads every joint: 0, 0.6, −1.2, 0.3 rad repeating, inside the joint limits.
Eigen::VectorXd sample_pose(const offline::ModelX& model) {
  const double pattern[] = {0.0, 0.6, -1.2, 0.3};
  Eigen::VectorXd q(model.joint_count());
  for (int j = 0; j < model.joint_count(); ++j)
    q[j] = std::clamp(pattern[j % 4], model.lower[j], model.upper[j]);
  return q;
}

std::string joint_list(const Eigen::VectorXd& v, const char* format) {
  std::string s;
  char item[32];
  for (Eigen::Index j = 0; j < v.size(); ++j) {
    std::snprintf(item, sizeof item, format, v[j]);
    s += (j ? " " : "") + std::string(item);
  }
  return s;
}

void print_summary(const std::string& robot_file) {
  const RobotDescription description = load_robot_description(robot_file);
  const offline::ModelX model = make_model<double, Eigen::Dynamic>(description);
  const int joints = model.joint_count();
  int prismatic = 0;
  for (int j = 0; j < joints; ++j)
    prismatic += model.is_prismatic(j) ? 1 : 0;
  std::printf(
      "robot '%s' from %s: %d joints (%d revolute, %d prismatic; a prismatic joint's "
      "rows read N for N·m, kg for kg·m², N/A for Nm/A)\n\n",
      model.name.c_str(), robot_file.c_str(), joints, joints - prismatic, prismatic);
  std::printf("%-8s %-17s %8s %12s %8s %9s %15s\n", "joint", "motor", "link", "mass [kg]", "ratio",
              "Kt [Nm/A]", "armature [kgm2]");
  for (int j = 0; j < joints; ++j) {
    std::printf("%-8s %-17s %8s %12.4f %8.1f %9.2f %15.4f\n", model.joint_names[j].c_str(),
                description.drives[j].motor.c_str(), model.link_names[j + 1].c_str(),
                model.inertias[j + 1].mass, model.gear_ratio(j), model.torque_constant(j),
                model.armature(j));
  }
  offline::DataX data(model);
  const Eigen::VectorXd q = sample_pose(model);
  const Eigen::VectorXd g = compute_gravity(model, data, q);
  const Eigen::MatrixXd M = compute_mass_matrix(model, data, q);
  forward_kinematics(model, data, q);  // the pads' world poses below
  std::printf("\nat q = [%s] rad:\n", joint_list(q, "%.2f").c_str());
  for (int j = 0; j < joints; ++j) {
    std::printf("  %s: gravity %8.3f N·m = %7.1f mA   M_jj %.4f kg·m² (%.0f %% armature)\n",
                model.joint_names[j].c_str(), g(j), 1000.0 * g(j) / model.torque_constant(j),
                M(j, j), 100.0 * model.armature(j) / M(j, j));
  }
  if (description.pads_file.empty()) {
    std::printf("\nno skin (the robot file names no pad layout)\n");
  } else {
    const auto pads = load_pads(description.pads_file, model);
    std::printf("\n%zu skin pads (%s):\n", pads.size(), description.pads_file.c_str());
    for (const Pad& pad : pads) {
      const Vector3<double> p = data.oMi[pad.link].apply(pad.center);
      const Jacobian<double, Eigen::Dynamic> J = point_jacobian(model, data, pad.link, p);
      // torque a 10 N push along the inward normal produces at the joints
      const Vector3<double> push = -10.0 * (data.oMi[pad.link].R * pad.normal);
      const Eigen::VectorXd tau = J.topRows<3>().transpose() * push;
      std::printf("  %-16s on %s, area %4.1f cm², 10 N push -> tau = [%s] N·m\n", pad.name.c_str(),
                  model.link_names[pad.link].c_str(), pad.area * 1e4,
                  joint_list(tau, "%6.2f").c_str());
    }
  }
}

}  // namespace

void print_robot_summary(const std::string& robot_file) {
  print_summary(robot_file);
}

void register_info_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("info", "Load a robot file and print its model, drives and pads");
  cmd->footer("Example: tpf info --robot data/arm4.robot.json");
  auto robot = std::make_shared<std::string>(offline::data_file("arm4.robot.json").string());
  cmd->add_option("--robot", *robot, "robot file (JSON naming the URDF and pad layout)")
      ->capture_default_str()
      ->check(input_file());
  cmd->callback([robot] { print_robot_summary(*robot); });
}

}  // namespace tpf::cli

TPF_UNOPTIMISED_WHEN_SANITIZED_END
