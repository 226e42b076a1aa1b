// Start-up code of the nominal model: column names, base parameters of a model, parameter files.

#include <cmath>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>

#include "core/common/atomic_file.hpp"
#include "core/common/json_object.hpp"
#include "core/common/unoptimised_when_sanitized.hpp"
#include "tpf/common/error.hpp"
#include "tpf/estimation/nominal_model.hpp"
#include "tpf/model/load_robot.hpp"

TPF_UNOPTIMISED_WHEN_SANITIZED_BEGIN

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

constexpr int X = Eigen::Dynamic;

Json matrix_to_json(const Eigen::MatrixXd& m) {
  Json a = Json::array();
  for (int r = 0; r < m.rows(); ++r)
    a.push_back(array_json(m.row(r).transpose().eval()));
  return a;
}

int column_by_name(int joints, const std::string& name) {
  for (int c = 0; c < 11 * joints; ++c)
    if (regressor_column_name(joints, c) == name) return c;
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
void require_every_base_parameter(const json::Object& top, const NominalModelX& nominal) {
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

BaseParameters rigid_body_base_parameters(const Model<double, X>& model) {
  constexpr int kStates = 200;
  const int n = model.joint_count();
  const int rigid = 11 * n;
  std::mt19937_64 rng(20240601);
  auto uniform = [&rng](double lo, double hi) {
    return lo + (hi - lo) * (static_cast<double>(rng() >> 11) * 0x1.0p-53);
  };
  Eigen::MatrixXd W(kStates * n, rigid);
  Data<double, X> data(model);
  Regressor<double, X> Y;
  for (int s = 0; s < kStates; ++s) {
    Eigen::VectorXd q(n), dq(n), ddq(n);
    for (int j = 0; j < n; ++j) {
      q[j] = model.has_position_limits(j) ? uniform(model.lower[j], model.upper[j])
                                          : uniform(-M_PI, M_PI);
      dq[j] = uniform(-2.0, 2.0);
      ddq[j] = uniform(-5.0, 5.0);
    }
    compute_regressor(model, data, q, dq, ddq, Y);
    W.middleRows(s * n, n) = Y.leftCols(rigid);
  }
  return find_base_parameters(W);
}

NominalModelX nominal_from_model(const Model<double, X>& model,
                                 const StribeckParameters<double, X>& friction) {
  const int n = model.joint_count();
  NominalModelX nominal;
  nominal.resize(n);
  nominal.model = model;
  nominal.friction = friction;
  const BaseParameters base = rigid_body_base_parameters(model);
  const Eigen::VectorXd pi =
      dynamic_parameters(model, Eigen::VectorXd::Zero(n), Eigen::VectorXd::Zero(n)).head(11 * n);
  const Eigen::VectorXd values = base.project(pi);
  nominal.base_count = base.size();
  for (int i = 0; i < base.size(); ++i) {
    nominal.base_columns[i] = base.independent[i];
    nominal.base_values[i] = values[i];
  }
  return nominal;
}

NominalModelX load_nominal_model(const std::filesystem::path& params_file,
                                 const std::filesystem::path& robot_file, int joints) {
  return load_nominal_model(params_file, load_robot_description(robot_file), joints);
}

NominalModelX load_nominal_model(const std::filesystem::path& params_file,
                                 const RobotDescription& description, int joints) {
  using Bound = json::Object::Bound;
  json::Object top = json::Object::read_document(params_file, kParamsFormat, kParamsVersion);
  if (top.number("version", 0, 1e9) < kParamsVersion)
    top.fail("version",
             "is 1: friction and added effects in the log's effort unit (mA for a log of "
             "currents); this tpf reads version 2, every torque in N*m. Convert the file with "
             "`tpf upgrade --params FILE` (or identify again)");
  require_robot(top, description);
  NominalModelX nominal;
  nominal.model = make_model<double, X>(description);
  const int n = nominal.model.joint_count();
  if (joints > 0 && joints != n)
    throw Error::at(description.source, 0, "joints",
                    "the robot file has " + std::to_string(n) + " joints, the program asks for " +
                        std::to_string(joints));
  top.require_joints(n);
  top.text("source", "");
  top.choice("torque_unit", "N*m", {"N*m"});
  nominal.resize(n);

  std::vector<json::Object> rigid = top.children("rigid_body");
  if (!top.has("rigid_body")) top.fail("rigid_body", "missing");
  if (rigid.size() > static_cast<std::size_t>(11 * n))
    top.fail("rigid_body", "must be an array of at most " + std::to_string(11 * n) + " parameters");
  for (std::size_t i = 0; i < rigid.size(); ++i) {
    json::Object& r = rigid[i];
    const std::string name = r.text("name");
    const int column = column_by_name(n, name);
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
  StribeckParameters<double, X>& p = nominal.friction;
  f.joint_vector("coulomb", p.coulomb, true, Bound::kNonNegative);
  f.joint_vector("static", p.static_friction, true, Bound::kNonNegative);
  f.joint_vector("stribeck_velocity", p.stribeck_velocity, true, Bound::kPositive);
  f.joint_vector("stribeck_exponent", p.stribeck_exponent, true, Bound::kPositive);
  f.joint_vector("viscous", p.viscous, true);
  f.joint_vector("load_coulomb", p.load_coulomb, false);
  f.joint_vector("load_viscous", p.load_viscous, false);
  f.joint_vector("coulomb_asymmetry", p.coulomb_asymmetry, false);
  f.joint_vector("viscous_asymmetry", p.viscous_asymmetry, false);
  f.joint_matrix("neighbour_load_coulomb", p.neighbour_load_coulomb);
  f.joint_matrix("neighbour_load_viscous", p.neighbour_load_viscous);
  for (int j = 0; j < n; ++j) {
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
  for_each_offline_only_effect([&added, n]<typename Effect>() { Effect::refuse(added, n); });
  added.finish();

  if (top.has("fit")) top.child("fit");  // free-form fit quality, for people
  top.finish();
  return nominal;
}

void save_nominal_model(const std::filesystem::path& params_file, const NominalModelX& nominal,
                        const std::string& source, const std::string& fit_quality_json) {
  const int n = nominal.model.joint_count();
  const std::string file = params_file.string();
  Json j;
  j["format"] = kParamsFormat;
  j["version"] = kParamsVersion;
  j["robot"] = nominal.model.name;
  j["joints"] = n;
  if (!source.empty()) j["source"] = source;
  j["torque_unit"] = "N*m";

  // Names and combinations of the base parameters, from the model's own base-parameter map.
  const BaseParameters base = rigid_body_base_parameters(nominal.model);
  std::vector<std::string> names;
  for (int c = 0; c < 11 * n; ++c)
    names.push_back(regressor_column_name(n, c));
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

  const StribeckParameters<double, X>& p = nominal.friction;
  j["friction"] = {{"coulomb", array_json(p.coulomb)},
                   {"static", array_json(p.static_friction)},
                   {"stribeck_velocity", array_json(p.stribeck_velocity)},
                   {"stribeck_exponent", array_json(p.stribeck_exponent)},
                   {"viscous", array_json(p.viscous)},
                   {"load_coulomb", array_json(p.load_coulomb)},
                   {"load_viscous", array_json(p.load_viscous)},
                   {"coulomb_asymmetry", array_json(p.coulomb_asymmetry)},
                   {"viscous_asymmetry", array_json(p.viscous_asymmetry)},
                   {"neighbour_load_coulomb", matrix_to_json(p.neighbour_load_coulomb)},
                   {"neighbour_load_viscous", matrix_to_json(p.neighbour_load_viscous)}};

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

}  // namespace tpf

TPF_UNOPTIMISED_WHEN_SANITIZED_END
