#include "offline/pipeline/declared_model.hpp"

#include "tpf/common/joint_counts.hpp"
#include "tpf/friction/friction_file.hpp"
#include "tpf/model/load_robot.hpp"

namespace tpf::offline {

template <int N>
NominalModel<double, N> declared_nominal_model(const std::filesystem::path& robot_file,
                                               const std::filesystem::path& friction_file,
                                               const std::string& effort_prefix) {
  const auto model = load_robot<double, N>(robot_file.string());
  auto friction = load_stribeck_parameters<double, N>(friction_file.string());  // N·m
  const JointVector<double, N> scale = effort_scale<N>(model, effort_prefix == "i" ? "mA" : "N*m");
  for (auto* v : {&friction.coulomb, &friction.static_friction, &friction.viscous,
                  &friction.load_coulomb, &friction.load_viscous})
    *v = v->cwiseProduct(scale);
  NominalModel<double, N> nominal = nominal_from_model<N>(model, friction, scale);
  nominal.effort_unit = effort_prefix == "i" ? "mA" : "N*m";
  return nominal;
}

#define TPF_INSTANTIATE_DECLARED_MODEL(N)                     \
  template NominalModel<double, N> declared_nominal_model<N>( \
      const std::filesystem::path&, const std::filesystem::path&, const std::string&);
TPF_FOR_EACH_JOINT_COUNT(TPF_INSTANTIATE_DECLARED_MODEL)
#undef TPF_INSTANTIATE_DECLARED_MODEL

}  // namespace tpf::offline
