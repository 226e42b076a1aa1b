// Start-up code of the nominal model: column names, base parameters of a model, parameter files.

#include <cmath>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>

#include "tpf/common/atomic_file.hpp"
#include "tpf/common/error.hpp"
#include "tpf/common/joint_counts.hpp"
#include "tpf/common/json_object.hpp"
#include "tpf/estimation/nominal_model.hpp"
#include "tpf/model/load_robot.hpp"

namespace tpf {
namespace {

using Json = nlohmann::json;

constexpr const char* kParamsFormat = "tpf-params";
constexpr int kParamsVersion = 2;  // 2: torques in N·m (1: in the log's effort unit)

Json array_json(const auto& v) {
  Json a = Json::array();
  for (Eigen::Index i = 0; i < v.size(); ++i)
    a.push_back(v[i]);
  return a;
}

template <int N>
Json matrix_to_json(const JointMatrix<double, N>& m) {
  Json a = Json::array();
  for (int r = 0; r < N; ++r)
    a.push_back(array_json(m.row(r).transpose().eval()));
  return a;
}

template <int N>
int column_by_name(const std::string& name) {
  for (int c = 0; c < 11 * N; ++c)
    if (regressor_column_name(N, c) == name) return c;
  return -1;
}

/// Fails when the file names a robot ("robot", the URDF's robot name when it was identified)
/// other than the robot file's (`description`): the parameters of another arm, or the
/// tools' default robot file where the user's was meant. Checked before the joint counts, so that
/// this is what is said.
void require_robot(json::Object& top, const RobotDescription& description) {
  const std::string robot = top.text("robot", "");
  if (robot.empty()) return;
  const std::string& name = description.chain.robot_name;
  if (robot != name)
    top.fail("robot", "'" + robot + "', but the robot file " + description.source + " is '" + name +
                          "': these parameters were identified for another arm (give its robot "
                          "file, --robot)");
}

/// Fails when the file's rigid_body gives fewer values than the robot file has base parameters:
/// the missing ones would silently be 0 (a link without weight or inertia). Which columns stand
/// for the base is the identification's choice, so only the count is checked.
template <int N>
void require_every_base_parameter(const json::Object& top, const NominalModel<double, N>& nominal) {
  const int expected = rigid_body_base_parameters(nominal.model).size();
  if (nominal.base_count < expected)
    top.fail("rigid_body", std::to_string(nominal.base_count) +
                               " parameters, but the robot file has " + std::to_string(expected) +
                               " base parameters and each needs a value (identify again)");
}

}  // namespace

std::string regressor_column_name(int joints, int column) {
  static const char* kLink[10] = {"m", "mx", "my", "mz", "Ixx", "Ixy", "Ixz", "Iyy", "Iyz", "Izz"};
  if (column < 10 * joints) return kLink[column % 10] + std::to_string(column / 10 + 1);
  const int j = column % joints + 1;
  if (column < 11 * joints) return "Ia" + std::to_string(j);
  if (column < 12 * joints) return "fc" + std::to_string(j);
  return "fv" + std::to_string(j);
}

template <int N>
BaseParameters rigid_body_base_parameters(const Model<double, N>& model) {
  constexpr int kStates = 200;
  constexpr int kRigid = 11 * N;
  std::mt19937_64 rng(20240601);
  auto uniform = [&rng](double lo, double hi) {
    return lo + (hi - lo) * (static_cast<double>(rng() >> 11) * 0x1.0p-53);
  };
  Eigen::MatrixXd W(kStates * N, kRigid);
  Data<double, N> data;
  Regressor<double, N> Y;
  for (int s = 0; s < kStates; ++s) {
    JointVector<double, N> q, dq, ddq;
    for (int j = 0; j < N; ++j) {
      q[j] = model.has_position_limits(j) ? uniform(model.lower[j], model.upper[j])
                                          : uniform(-M_PI, M_PI);
      dq[j] = uniform(-2.0, 2.0);
      ddq[j] = uniform(-5.0, 5.0);
    }
    compute_regressor(model, data, q, dq, ddq, Y);
    W.middleRows(s * N, N) = Y.leftCols(kRigid);
  }
  return find_base_parameters(W);
}

template <int N>
NominalModel<double, N> nominal_from_model(const Model<double, N>& model,
                                           const StribeckParameters<double, N>& friction) {
  NominalModel<double, N> nominal;
  nominal.model = model;
  nominal.friction = friction;
  const BaseParameters base = rigid_body_base_parameters(model);
  const Eigen::VectorXd pi =
      dynamic_parameters(model, JointVector<double, N>::Zero(), JointVector<double, N>::Zero())
          .head(11 * N);
  const Eigen::VectorXd values = base.project(pi);
  nominal.base_count = base.size();
  for (int i = 0; i < base.size(); ++i) {
    nominal.base_columns[i] = base.independent[i];
    nominal.base_values[i] = values[i];
  }
  return nominal;
}

template <int N>
NominalModel<double, N> load_nominal_model(const std::filesystem::path& params_file,
                                           const std::filesystem::path& robot_file) {
  return load_nominal_model<N>(params_file, load_robot_description(robot_file));
}

template <int N>
NominalModel<double, N> load_nominal_model(const std::filesystem::path& params_file,
                                           const RobotDescription& description) {
  using Bound = json::Object::Bound;
  json::Object top = json::Object::read_document(params_file, kParamsFormat, kParamsVersion);
  if (top.number("version", 0, 1e9) < kParamsVersion)
    top.fail("version",
             "is 1: friction and added effects in the log's effort unit (mA for a log of "
             "currents); this tpf reads version 2, every torque in N*m. Convert the file with "
             "`tpf upgrade --params FILE` (or identify again)");
  require_robot(top, description);
  top.require_joints(N);
  top.text("source", "");
  top.choice("torque_unit", "N*m", {"N*m"});

  NominalModel<double, N> nominal;
  nominal.model = make_model<double, N>(description);

  std::vector<json::Object> rigid = top.children("rigid_body");
  if (!top.has("rigid_body")) top.fail("rigid_body", "missing");
  if (rigid.size() > static_cast<std::size_t>(11 * N))
    top.fail("rigid_body", "must be an array of at most " + std::to_string(11 * N) + " parameters");
  for (std::size_t i = 0; i < rigid.size(); ++i) {
    json::Object& r = rigid[i];
    const std::string name = r.text("name");
    const int column = column_by_name<N>(name);
    if (column < 0) r.fail("name", "unknown rigid-body parameter '" + name + "'");
    for (std::size_t k = 0; k < i; ++k)
      if (nominal.base_columns[k] == column) r.fail("name", "'" + name + "' appears twice");
    nominal.base_columns[i] = column;
    nominal.base_values[i] = r.number("value", -json::Object::kInfinity, json::Object::kInfinity);
    r.text("combination", "");
    r.finish();
  }
  nominal.base_count = static_cast<int>(rigid.size());
  require_every_base_parameter(top, nominal);

  if (!top.has("friction")) top.fail("friction", "missing");
  json::Object f = top.child("friction");
  StribeckParameters<double, N>& p = nominal.friction;
  f.joint_vector<N>("coulomb", p.coulomb, true, Bound::kNonNegative);
  f.joint_vector<N>("static", p.static_friction, true, Bound::kNonNegative);
  f.joint_vector<N>("stribeck_velocity", p.stribeck_velocity, true, Bound::kPositive);
  f.joint_vector<N>("stribeck_exponent", p.stribeck_exponent, true, Bound::kPositive);
  f.joint_vector<N>("viscous", p.viscous, true);
  f.joint_vector<N>("load_coulomb", p.load_coulomb, false);
  f.joint_vector<N>("load_viscous", p.load_viscous, false);
  f.joint_vector<N>("coulomb_asymmetry", p.coulomb_asymmetry, false);
  f.joint_vector<N>("viscous_asymmetry", p.viscous_asymmetry, false);
  f.joint_matrix<N>("neighbour_load_coulomb", p.neighbour_load_coulomb);
  f.joint_matrix<N>("neighbour_load_viscous", p.neighbour_load_viscous);
  for (int j = 0; j < N; ++j) {
    if (p.neighbour_load_coulomb(j, j) != 0.0 || p.neighbour_load_viscous(j, j) != 0.0)
      f.fail("neighbour_load_coulomb",
             "the diagonal must be zero (a joint's own load is load_coulomb / load_viscous)");
    if (std::abs(p.coulomb_asymmetry[j]) > p.coulomb[j])
      f.fail("coulomb_asymmetry[" + std::to_string(j) + "]",
             "must not exceed coulomb in magnitude (friction would push the motion)");
  }
  f.finish();

  json::Object added = top.child("added_effects");
  nominal.added.for_each([&added](auto& effect) { effect.read(added); });
  for_each_offline_only_effect([&added]<typename Effect>() { Effect::template refuse<N>(added); });
  added.finish();

  if (top.has("fit")) top.child("fit");  // free-form fit quality, for people
  top.finish();
  return nominal;
}

template <int N>
void save_nominal_model(const std::filesystem::path& params_file,
                        const NominalModel<double, N>& nominal, const std::string& source,
                        const std::string& fit_quality_json) {
  const std::string file = params_file.string();
  Json j;
  j["format"] = kParamsFormat;
  j["version"] = kParamsVersion;
  j["robot"] = nominal.model.name;
  j["joints"] = N;
  if (!source.empty()) j["source"] = source;
  j["torque_unit"] = "N*m";

  // Names and combinations of the base parameters, from the model's own base-parameter map.
  const BaseParameters base = rigid_body_base_parameters(nominal.model);
  std::vector<std::string> names;
  for (int c = 0; c < 11 * N; ++c)
    names.push_back(regressor_column_name(N, c));
  Json rigid = Json::array();
  for (int i = 0; i < nominal.base_count; ++i) {
    Json p;
    const int column = nominal.base_columns[i];
    p["name"] = names[column];
    p["value"] = nominal.base_values[i];
    for (int b = 0; b < base.size(); ++b)
      if (base.independent[b] == column) p["combination"] = base.describe(b, names);
    rigid.push_back(p);
  }
  j["rigid_body"] = rigid;

  const StribeckParameters<double, N>& p = nominal.friction;
  j["friction"] = {{"coulomb", array_json(p.coulomb)},
                   {"static", array_json(p.static_friction)},
                   {"stribeck_velocity", array_json(p.stribeck_velocity)},
                   {"stribeck_exponent", array_json(p.stribeck_exponent)},
                   {"viscous", array_json(p.viscous)},
                   {"load_coulomb", array_json(p.load_coulomb)},
                   {"load_viscous", array_json(p.load_viscous)},
                   {"coulomb_asymmetry", array_json(p.coulomb_asymmetry)},
                   {"viscous_asymmetry", array_json(p.viscous_asymmetry)},
                   {"neighbour_load_coulomb", matrix_to_json<N>(p.neighbour_load_coulomb)},
                   {"neighbour_load_viscous", matrix_to_json<N>(p.neighbour_load_viscous)}};

  Json added = Json::object();
  nominal.added.for_each([&added](const auto& effect) { effect.write(added); });
  j["added_effects"] = added;
  if (!fit_quality_json.empty()) {
    try {
      j["fit"] = Json::parse(fit_quality_json);
    } catch (const Json::exception& ex) {
      throw Error::at(file, 0, "fit", std::string("not valid JSON: ") + ex.what());
    }
  }

  json::require_finite(j, params_file);
  write_file_atomically(params_file, j.dump(2) + "\n");
}

#define TPF_INSTANTIATE_NOMINAL_MODEL(N)                                                        \
  template BaseParameters rigid_body_base_parameters<N>(const Model<double, N>&);               \
  template NominalModel<double, N> nominal_from_model<N>(const Model<double, N>&,               \
                                                         const StribeckParameters<double, N>&); \
  template NominalModel<double, N> load_nominal_model<N>(const std::filesystem::path&,          \
                                                         const std::filesystem::path&);         \
  template NominalModel<double, N> load_nominal_model<N>(const std::filesystem::path&,          \
                                                         const RobotDescription&);              \
  template void save_nominal_model<N>(const std::filesystem::path&,                             \
                                      const NominalModel<double, N>&, const std::string&,       \
                                      const std::string&);
TPF_FOR_EACH_JOINT_COUNT(TPF_INSTANTIATE_NOMINAL_MODEL)
#undef TPF_INSTANTIATE_NOMINAL_MODEL

}  // namespace tpf
