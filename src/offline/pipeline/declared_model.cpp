#include "offline/pipeline/declared_model.hpp"

#include "tpf/friction/friction_file.hpp"
#include "tpf/model/load_robot.hpp"

namespace tpf::offline {

ArmNominal declared_nominal_model(const std::filesystem::path& robot_file,
                                  const std::filesystem::path& friction_file,
                                  const std::string& effort_prefix) {
  const auto model = load_robot<double, kArmJoints>(robot_file.string());
  auto friction = load_stribeck_parameters<double, kArmJoints>(friction_file.string());  // N·m
  const JointVector<double, kArmJoints> scale =
      effort_scale<kArmJoints>(model, effort_prefix == "i" ? "mA" : "N*m");
  for (auto* v : {&friction.coulomb, &friction.static_friction, &friction.viscous,
                  &friction.load_coulomb, &friction.load_viscous})
    *v = v->cwiseProduct(scale);
  ArmNominal nominal = nominal_from_model<kArmJoints>(model, friction, scale);
  nominal.effort_unit = effort_prefix == "i" ? "mA" : "N*m";
  return nominal;
}

}  // namespace tpf::offline
