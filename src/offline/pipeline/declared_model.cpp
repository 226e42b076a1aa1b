#include "offline/pipeline/declared_model.hpp"

#include "tpf/common/error.hpp"
#include "tpf/friction/friction_file.hpp"
#include "tpf/model/load_robot.hpp"

namespace tpf::offline {

NominalModelX declared_nominal_model(const std::filesystem::path& robot_file,
                                     const std::filesystem::path& friction_file) {
  const ModelX model = load_robot<double, Eigen::Dynamic>(robot_file.string());
  if (friction_effort_unit(friction_file.string()) != "N*m")
    throw Error::at(friction_file.string(), 0, "effort_unit", "a declared friction must be in N*m");
  return nominal_from_model(model,
                            load_stribeck_parameters(friction_file.string(), model.joint_count()));
}

}  // namespace tpf::offline
