// `tpf info`: load a robot and print its model and a few computed quantities.
#include <cstdio>
#include <iostream>

#include "commands.hpp"
#include "offline/common/data_files.hpp"
#include "tpf/core.hpp"

namespace tpf::cli {

void print_robot_summary(const std::string& robot_file) {
  constexpr int kJoints = 4;
  const auto model = load_robot<double, kJoints>(robot_file);
  const RobotDescription description = load_robot_description(robot_file);
  std::printf("robot '%s' from %s: %d revolute joints\n\n", model.name.c_str(), robot_file.c_str(),
              kJoints);
  std::printf("%-8s %-17s %8s %12s %8s %9s %15s\n", "joint", "motor", "link", "mass [kg]", "ratio",
              "Kt [Nm/A]", "armature [kgm2]");
  for (int j = 0; j < kJoints; ++j) {
    std::printf("%-8s %-17s %8s %12.4f %8.1f %9.2f %15.4f\n", model.joint_names[j].c_str(),
                description.drives[j].motor.c_str(), model.link_names[j + 1].c_str(),
                model.inertias[j + 1].mass, model.gear_ratio(j), model.torque_constant(j),
                model.armature(j));
  }
  Data<double, kJoints> data(model);
  JointVector<double, kJoints> q;
  q << 0.0, 0.6, -1.2, 0.3;
  const auto g = compute_gravity(model, data, q);
  const auto M = compute_mass_matrix(model, data, q);
  std::printf("\nat q = [%.2f %.2f %.2f %.2f] rad:\n", q(0), q(1), q(2), q(3));
  for (int j = 0; j < kJoints; ++j) {
    std::printf("  %s: gravity %8.3f N·m = %7.1f mA   M_jj %.4f kg·m² (%.0f %% armature)\n",
                model.joint_names[j].c_str(), g(j), 1000.0 * g(j) / model.torque_constant(j),
                M(j, j), 100.0 * model.armature(j) / M(j, j));
  }
  if (!description.pads_file.empty()) {
    const auto pads = load_pads(description.pads_file, model);
    std::printf("\n%zu skin pads (%s):\n", pads.size(), description.pads_file.c_str());
    for (const Pad& pad : pads) {
      const Vector3<double> p = data.oMi[pad.link].apply(pad.center);
      const Jacobian<double, kJoints> J = point_jacobian(model, data, pad.link, p);
      // torque a 10 N push along the inward normal produces at the joints
      const Vector3<double> push = -10.0 * (data.oMi[pad.link].R * pad.normal);
      const JointVector<double, kJoints> tau = J.topRows<3>().transpose() * push;
      std::printf(
          "  %-16s on %s, area %4.1f cm², 10 N push -> tau = [%6.2f %6.2f %6.2f %6.2f] N·m\n",
          pad.name.c_str(), model.link_names[pad.link].c_str(), pad.area * 1e4, tau(0), tau(1),
          tau(2), tau(3));
    }
  }
}

void register_info_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("info", "Load a robot file and print its model, drives and pads");
  auto robot = std::make_shared<std::string>(offline::data_file("arm4.robot.json").string());
  cmd->add_option("--robot", *robot, "robot file (JSON naming the URDF and pad layout)")
      ->capture_default_str()
      ->check(CLI::ExistingFile);
  cmd->callback([robot] { print_robot_summary(*robot); });
}

}  // namespace tpf::cli
