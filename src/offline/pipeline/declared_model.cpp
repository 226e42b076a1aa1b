#include "offline/pipeline/declared_model.hpp"

#include "tpf/common/error.hpp"
#include "tpf/common/joint_counts.hpp"
#include "tpf/friction/friction_file.hpp"
#include "tpf/model/load_robot.hpp"

namespace tpf::offline {

template <int N>
NominalModel<double, N> declared_nominal_model(const std::filesystem::path& robot_file,
                                               const std::filesystem::path& friction_file) {
  const auto model = load_robot<double, N>(robot_file.string());
  if (friction_effort_unit(friction_file.string()) != "N*m")
    throw Error::at(friction_file.string(), 0, "effort_unit", "a declared friction must be in N*m");
  return nominal_from_model<N>(model, load_stribeck_parameters<double, N>(friction_file.string()));
}

#define TPF_INSTANTIATE_DECLARED_MODEL(N)                                                  \
  template NominalModel<double, N> declared_nominal_model<N>(const std::filesystem::path&, \
                                                             const std::filesystem::path&);
TPF_FOR_EACH_JOINT_COUNT(TPF_INSTANTIATE_DECLARED_MODEL)
#undef TPF_INSTANTIATE_DECLARED_MODEL

}  // namespace tpf::offline
