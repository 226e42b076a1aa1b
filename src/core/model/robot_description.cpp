#include "tpf/model/robot_description.hpp"

#include <nlohmann/json.hpp>

#include "tpf/common/error.hpp"
#include "tpf/common/json_file.hpp"

namespace tpf {

RobotDescription load_robot_description(const std::filesystem::path& robot_file) {
  const std::string file = robot_file.string();
  const nlohmann::json j = json::read_file(robot_file);
  json::check_format(j, file, "tpf-robot", 1);
  json::only_keys(j, file, "",
                  {"format", "version", "name", "urdf", "pads", "gravity", "joints", "units"});

  RobotDescription robot;
  robot.source = file;
  const std::filesystem::path folder = robot_file.parent_path();
  robot.chain = load_urdf_chain(folder / json::string(j, file, "", "urdf"));
  if (j.contains("name")) robot.chain.robot_name = json::string(j, file, "", "name");
  if (j.contains("gravity")) robot.gravity = json::vector3(j, file, "", "gravity");
  if (j.contains("pads")) robot.pads_file = folder / json::string(j, file, "", "pads");

  const nlohmann::json& joints = json::member(j, file, "", "joints");
  if (!joints.is_array() || joints.size() != robot.chain.joints.size()) {
    throw Error::at(file, 0, "joints",
                    "must list the " + std::to_string(robot.chain.joints.size()) + " joints of " +
                        robot.chain.source + " in chain order");
  }
  for (std::size_t k = 0; k < joints.size(); ++k) {
    const std::string where = "joints[" + std::to_string(k) + "]";
    const nlohmann::json& jj = joints[k];
    json::only_keys(
        jj, file, where,
        {"name", "motor", "gear_ratio", "rotor_inertia", "torque_constant", "current_limit"});
    DriveDescription d;
    d.joint = json::string(jj, file, where, "name");
    if (d.joint != robot.chain.joints[k].name) {
      throw Error::at(file, 0, where + ".name",
                      "is '" + d.joint + "' but joint " + std::to_string(k + 1) +
                          " of the URDF is '" + robot.chain.joints[k].name + "'");
    }
    d.motor = jj.contains("motor") ? json::string(jj, file, where, "motor") : "";
    d.gear_ratio = json::number(jj, file, where, "gear_ratio");
    d.rotor_inertia = json::number(jj, file, where, "rotor_inertia");
    d.torque_constant = json::number(jj, file, where, "torque_constant");
    d.current_limit = json::number(jj, file, where, "current_limit");
    if (d.gear_ratio <= 0) throw Error::at(file, 0, where + ".gear_ratio", "must be > 0");
    if (d.rotor_inertia < 0) throw Error::at(file, 0, where + ".rotor_inertia", "must be >= 0");
    if (d.torque_constant <= 0) throw Error::at(file, 0, where + ".torque_constant", "must be > 0");
    if (d.current_limit <= 0) throw Error::at(file, 0, where + ".current_limit", "must be > 0");
    robot.drives.push_back(d);
  }
  return robot;
}

}  // namespace tpf
