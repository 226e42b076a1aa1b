#include "tpf/model/robot_description.hpp"

#include <Eigen/LU>
#include <cmath>
#include <limits>

#include "core/common/json_object.hpp"
#include "core/common/unoptimised_when_sanitized.hpp"
#include "tpf/common/error.hpp"

TPF_UNOPTIMISED_WHEN_SANITIZED_BEGIN

namespace tpf {
namespace {

// A drive's "coupled_to": {"<joint>": c, …}: other joints of the chain, finite coefficients.
std::vector<std::pair<std::string, double>> coupled_joints(json::Object c,
                                                           const ChainDescription& chain,
                                                           std::size_t own) {
  std::vector<std::pair<std::string, double>> out;
  for (std::size_t k = 0; k < chain.joints.size(); ++k) {
    const std::string& name = chain.joints[k].name;
    if (!c.has(name)) continue;
    if (k == own) c.fail(name, "is the motor's own joint (its coefficient is 1)");
    out.emplace_back(name, c.number(name, -json::Object::kInfinity, json::Object::kInfinity));
  }
  c.finish();  // names a key that is no joint of the chain
  return out;
}

// C from the drives (row m: motor m, 1 on its own joint); refused when singular.
Eigen::MatrixXd coupling_matrix(const RobotDescription& robot, json::Object& top) {
  const auto n = static_cast<Eigen::Index>(robot.drives.size());
  Eigen::MatrixXd c = Eigen::MatrixXd::Identity(n, n);
  for (Eigen::Index m = 0; m < n; ++m)
    for (const auto& [joint, coefficient] : robot.drives[m].coupled_to)
      for (Eigen::Index k = 0; k < n; ++k)
        if (robot.chain.joints[k].name == joint) c(m, k) = coefficient;
  if (n > 0 && !c.isIdentity(0.0)) {
    const Eigen::FullPivLU<Eigen::MatrixXd> lu(c);
    if (lu.rank() < n)
      top.fail("joints",
               "the motors' coupled_to make a singular coupling: the motors cannot "
               "move every joint on its own");
  }
  return c;
}

}  // namespace

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
    d.gear_ratio = j.number("gear_ratio", -kInf, kInf);
    if (std::abs(d.gear_ratio) < 1e-9) j.fail("gear_ratio", "must not be 0");
    if (j.has("coupled_to")) d.coupled_to = coupled_joints(j.child("coupled_to"), robot.chain, k);
    d.rotor_inertia = j.number("rotor_inertia", 0.0, kInf);
    d.torque_constant = j.number("torque_constant", 1e-9, kInf);
    d.current_limit = j.number("current_limit", 1e-9, kInf);
    j.finish();
    robot.drives.push_back(d);
  }
  robot.coupling = coupling_matrix(robot, top);
  top.finish();
  return robot;
}

}  // namespace tpf

TPF_UNOPTIMISED_WHEN_SANITIZED_END
