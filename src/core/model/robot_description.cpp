#include "tpf/model/robot_description.hpp"

#include <limits>

#include "core/common/json_object.hpp"
#include "tpf/common/error.hpp"

namespace tpf {

RobotDescription load_robot_description(const std::filesystem::path& robot_file) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  json::Object top = json::Object::read_document(robot_file, "tpf-robot", 1);
  top.child("units");  // documentation only

  RobotDescription robot;
  robot.source = robot_file.string();
  const std::filesystem::path folder = robot_file.parent_path();
  const std::string urdf = top.text("urdf");
  ChainEnds ends{top.text("root_link", ""), top.text("tip_link", ""), robot.source};
  robot.chain = load_urdf_chain(folder / urdf, ends);
  robot.chain.robot_name = top.text("name", robot.chain.robot_name);
  if (top.has("gravity")) robot.gravity = top.vector3("gravity");
  if (top.has("pads")) robot.pads_file = folder / top.text("pads");
  if (top.has("friction")) robot.friction_file = folder / top.text("friction");

  std::vector<json::Object> joints = top.children("joints");
  if (joints.size() != robot.chain.joints.size()) {
    top.fail("joints", "must list the " + std::to_string(robot.chain.joints.size()) +
                           " joints of " + robot.chain.source + " in chain order");
  }
  for (std::size_t k = 0; k < joints.size(); ++k) {
    json::Object& j = joints[k];
    DriveDescription d;
    d.joint = j.text("name");
    if (d.joint != robot.chain.joints[k].name) {
      j.fail("name", "is '" + d.joint + "' but joint " + std::to_string(k + 1) +
                         " of the URDF is '" + robot.chain.joints[k].name + "'");
    }
    d.motor = j.text("motor", "");
    d.gear_ratio = j.number("gear_ratio", 1e-9, kInf);
    d.rotor_inertia = j.number("rotor_inertia", 0.0, kInf);
    d.torque_constant = j.number("torque_constant", 1e-9, kInf);
    d.current_limit = j.number("current_limit", 1e-9, kInf);
    j.finish();
    robot.drives.push_back(d);
  }
  top.finish();
  return robot;
}

}  // namespace tpf
