// Start-up code of the nominal model: column names, base parameters of a model, parameter files.
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <system_error>

#include "tpf/common/error.hpp"
#include "tpf/common/json_file.hpp"
#include "tpf/estimation/nominal_model.hpp"
#include "tpf/model/load_robot.hpp"

namespace tpf {
namespace {

using Json = nlohmann::json;

constexpr const char* kFormat = "tpf-params";
constexpr int kVersion = 1;

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

// Reads an array of N finite numbers; `min` is the smallest allowed value (−inf for none) and
// `strict` makes it exclusive.
template <int N>
void read_vector(const Json& parent, const std::string& file, const std::string& where,
                 const std::string& key, JointVector<double, N>& out, bool required,
                 double min = -INFINITY, bool strict = false) {
  if (!parent.contains(key)) {
    if (required) throw Error::at(file, 0, where + "." + key, "missing");
    return;
  }
  const Json& a = parent.at(key);
  const std::string field = where.empty() ? key : where + "." + key;
  if (!a.is_array() || a.size() != static_cast<std::size_t>(N))
    throw Error::at(file, 0, field, "must be an array of " + std::to_string(N) + " numbers");
  for (int i = 0; i < N; ++i) {
    const std::string item = field + "[" + std::to_string(i) + "]";
    if (!a[i].is_number()) throw Error::at(file, 0, item, "must be a number");
    const double v = a[i].get<double>();
    if (!std::isfinite(v)) throw Error::at(file, 0, item, "must be finite");
    if (v < min || (strict && v == min))
      throw Error::at(file, 0, item,
                      "must be " + std::string(strict ? "> " : ">= ") + std::to_string(min) +
                          ", got " + std::to_string(v));
    out[i] = v;
  }
}

template <int N>
void read_matrix(const Json& parent, const std::string& file, const std::string& where,
                 const std::string& key, JointMatrix<double, N>& out) {
  if (!parent.contains(key)) return;
  const Json& a = parent.at(key);
  const std::string field = where + "." + key;
  if (!a.is_array() || a.size() != static_cast<std::size_t>(N))
    throw Error::at(file, 0, field, "must be an array of " + std::to_string(N) + " rows");
  Json rows = Json::object();
  for (int r = 0; r < N; ++r) {
    rows["row"] = a[r];
    JointVector<double, N> v;
    read_vector<N>(rows, file, field + "[" + std::to_string(r) + "]", "row", v, true);
    out.row(r) = v.transpose();
  }
}

template <int N>
int column_by_name(const std::string& name) {
  for (int c = 0; c < 11 * N; ++c)
    if (regressor_column_name(N, c) == name) return c;
  return -1;
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
      const bool limited = model.upper[j] > model.lower[j];
      q[j] = limited ? uniform(model.lower[j], model.upper[j]) : uniform(-M_PI, M_PI);
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
                                           const StribeckParameters<double, N>& friction,
                                           const JointVector<double, N>& effort_per_newton_metre) {
  NominalModel<double, N> nominal;
  nominal.model = model;
  nominal.friction = friction;
  nominal.effort_per_newton_metre = effort_per_newton_metre;
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
JointVector<double, N> effort_scale(const Model<double, N>& model, const std::string& effort_unit) {
  if (effort_unit == "N*m") return JointVector<double, N>::Ones();
  if (effort_unit == "mA") return model.torque_constant.cwiseInverse() * 1000.0;
  throw Error("effort unit must be \"mA\" or \"N*m\", got \"" + effort_unit + "\"");
}

template <int N>
NominalModel<double, N> load_nominal_model(const std::filesystem::path& params_file,
                                           const std::filesystem::path& robot_file) {
  const std::string file = params_file.string();
  const Json j = json::read_file(params_file);
  json::check_format(j, file, kFormat, kVersion);
  json::only_keys(j, file, "",
                  {"format", "version", "robot", "joints", "source", "effort_unit",
                   "effort_per_newton_metre", "rigid_body", "friction", "added_effects", "fit"});
  const double joints = json::number(j, file, "", "joints");
  if (joints != N)
    throw Error::at(file, 0, "joints",
                    "the file is for " + std::to_string(static_cast<int>(joints)) +
                        " joints, this program is built for " + std::to_string(N));

  NominalModel<double, N> nominal;
  nominal.model = load_robot<double, N>(robot_file);
  nominal.effort_unit = json::string(j, file, "", "effort_unit");
  if (nominal.effort_unit != "mA" && nominal.effort_unit != "N*m")
    throw Error::at(file, 0, "effort_unit", "must be \"mA\" or \"N*m\"");
  read_vector<N>(j, file, "", "effort_per_newton_metre", nominal.effort_per_newton_metre, true, 0.0,
                 true);

  const Json& rigid = json::member(j, file, "", "rigid_body");
  if (!rigid.is_array() || rigid.size() > static_cast<std::size_t>(11 * N))
    throw Error::at(file, 0, "rigid_body",
                    "must be an array of at most " + std::to_string(11 * N) + " parameters");
  for (std::size_t i = 0; i < rigid.size(); ++i) {
    const std::string where = "rigid_body[" + std::to_string(i) + "]";
    json::only_keys(rigid[i], file, where, {"name", "value", "combination"});
    const std::string name = json::string(rigid[i], file, where, "name");
    const int column = column_by_name<N>(name);
    if (column < 0)
      throw Error::at(file, 0, where + ".name", "unknown rigid-body parameter '" + name + "'");
    for (std::size_t k = 0; k < i; ++k)
      if (nominal.base_columns[k] == column)
        throw Error::at(file, 0, where + ".name", "'" + name + "' appears twice");
    nominal.base_columns[i] = column;
    nominal.base_values[i] = json::number(rigid[i], file, where, "value");
  }
  nominal.base_count = static_cast<int>(rigid.size());

  const Json& f = json::member(j, file, "", "friction");
  json::only_keys(f, file, "friction",
                  {"coulomb", "static", "stribeck_velocity", "stribeck_exponent", "viscous",
                   "load_coulomb", "load_viscous"});
  StribeckParameters<double, N>& p = nominal.friction;
  read_vector<N>(f, file, "friction", "coulomb", p.coulomb, true, 0.0);
  read_vector<N>(f, file, "friction", "static", p.static_friction, true, 0.0);
  read_vector<N>(f, file, "friction", "stribeck_velocity", p.stribeck_velocity, true, 0.0, true);
  read_vector<N>(f, file, "friction", "stribeck_exponent", p.stribeck_exponent, true, 0.0, true);
  read_vector<N>(f, file, "friction", "viscous", p.viscous, true);
  read_vector<N>(f, file, "friction", "load_coulomb", p.load_coulomb, false);
  read_vector<N>(f, file, "friction", "load_viscous", p.load_viscous, false);

  if (j.contains("added_effects")) {
    const Json& a = j.at("added_effects");
    const std::string w = "added_effects";
    json::only_keys(
        a, file, w,
        {"ripple", "spring_stiffness", "spring_offset", "coupling_velocity",
         "coupling_acceleration", "thermal_viscous", "reference_temperature", "effort_delay_s"});
    AddedEffects<double, N>& e = nominal.added;
    read_vector<N>(a, file, w, "spring_stiffness", e.spring_stiffness, false);
    read_vector<N>(a, file, w, "spring_offset", e.spring_offset, false);
    read_matrix<N>(a, file, w, "coupling_velocity", e.coupling_velocity);
    read_matrix<N>(a, file, w, "coupling_acceleration", e.coupling_acceleration);
    read_vector<N>(a, file, w, "thermal_viscous", e.thermal_viscous, false);
    if (a.contains("reference_temperature"))
      e.reference_temperature = json::number(a, file, w, "reference_temperature");
    if (a.contains("effort_delay_s")) {
      e.effort_delay_s = json::number(a, file, w, "effort_delay_s");
      if (e.effort_delay_s < 0.0 || e.effort_delay_s > 1.0)
        throw Error::at(file, 0, w + ".effort_delay_s", "must be in [0, 1] s");
    }
    if (a.contains("ripple")) {
      const Json& r = a.at("ripple");
      if (!r.is_array() || r.size() > AddedEffects<double, N>::kMaxRippleTerms)
        throw Error::at(file, 0, w + ".ripple",
                        "must be an array of at most " +
                            std::to_string(AddedEffects<double, N>::kMaxRippleTerms) + " terms");
      for (std::size_t i = 0; i < r.size(); ++i) {
        const std::string where = w + ".ripple[" + std::to_string(i) + "]";
        json::only_keys(r[i], file, where, {"joint", "cycles_per_rev", "motor_side", "sin", "cos"});
        RippleTerm<double>& t = e.ripple[i];
        const double joint = json::number(r[i], file, where, "joint");
        if (joint < 1 || joint > N || joint != std::floor(joint))
          throw Error::at(file, 0, where + ".joint",
                          "must be a joint number 1.." + std::to_string(N));
        t.joint = static_cast<int>(joint) - 1;
        t.cycles_per_rev = json::number(r[i], file, where, "cycles_per_rev");
        if (t.cycles_per_rev <= 0)
          throw Error::at(file, 0, where + ".cycles_per_rev", "must be positive");
        if (r[i].contains("motor_side")) {
          if (!r[i].at("motor_side").is_boolean())
            throw Error::at(file, 0, where + ".motor_side", "must be true or false");
          t.motor_side = r[i].at("motor_side").get<bool>();
        }
        t.sin_amplitude = json::number(r[i], file, where, "sin");
        t.cos_amplitude = json::number(r[i], file, where, "cos");
      }
      e.ripple_count = static_cast<int>(r.size());
    }
  }
  if (j.contains("fit") && !j.at("fit").is_object())
    throw Error::at(file, 0, "fit", "must be an object");
  return nominal;
}

template <int N>
void save_nominal_model(const std::filesystem::path& params_file,
                        const NominalModel<double, N>& nominal, const std::string& source,
                        const std::string& fit_quality_json) {
  const std::string file = params_file.string();
  Json j;
  j["format"] = kFormat;
  j["version"] = kVersion;
  j["robot"] = nominal.model.name;
  j["joints"] = N;
  if (!source.empty()) j["source"] = source;
  j["effort_unit"] = nominal.effort_unit;
  j["effort_per_newton_metre"] = array_json(nominal.effort_per_newton_metre);

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
                   {"load_viscous", array_json(p.load_viscous)}};

  const AddedEffects<double, N>& e = nominal.added;
  Json ripple = Json::array();
  for (int i = 0; i < e.ripple_count; ++i)
    ripple.push_back({{"joint", e.ripple[i].joint + 1},
                      {"cycles_per_rev", e.ripple[i].cycles_per_rev},
                      {"motor_side", e.ripple[i].motor_side},
                      {"sin", e.ripple[i].sin_amplitude},
                      {"cos", e.ripple[i].cos_amplitude}});
  j["added_effects"] = {{"ripple", ripple},
                        {"spring_stiffness", array_json(e.spring_stiffness)},
                        {"spring_offset", array_json(e.spring_offset)},
                        {"coupling_velocity", matrix_to_json<N>(e.coupling_velocity)},
                        {"coupling_acceleration", matrix_to_json<N>(e.coupling_acceleration)},
                        {"thermal_viscous", array_json(e.thermal_viscous)},
                        {"reference_temperature", e.reference_temperature},
                        {"effort_delay_s", e.effort_delay_s}};
  if (!fit_quality_json.empty()) {
    try {
      j["fit"] = Json::parse(fit_quality_json);
    } catch (const Json::exception& ex) {
      throw Error::at(file, 0, "fit", std::string("not valid JSON: ") + ex.what());
    }
  }

  // Atomic: write a temporary beside the target, then rename it into place.
  const std::filesystem::path dir = params_file.has_parent_path() ? params_file.parent_path() : ".";
  const std::filesystem::path temp =
      dir / ("." + params_file.filename().string() + ".tmp." + std::to_string(::getpid()));
  {
    std::ofstream out(temp);
    if (!out) throw Error::at(file, 0, "", "cannot create the temporary file " + temp.string());
    out << j.dump(2) << "\n";
    if (!out.flush()) throw Error::at(file, 0, "", "write failed");
  }
  std::error_code ec;
  std::filesystem::rename(temp, params_file, ec);
  if (ec) {
    std::filesystem::remove(temp, ec);
    throw Error::at(file, 0, "", "cannot rename the temporary file into place");
  }
}

#define TPF_INSTANTIATE_NOMINAL_MODEL(N)                                                        \
  template BaseParameters rigid_body_base_parameters<N>(const Model<double, N>&);               \
  template NominalModel<double, N> nominal_from_model<N>(const Model<double, N>&,               \
                                                         const StribeckParameters<double, N>&,  \
                                                         const JointVector<double, N>&);        \
  template JointVector<double, N> effort_scale<N>(const Model<double, N>&, const std::string&); \
  template NominalModel<double, N> load_nominal_model<N>(const std::filesystem::path&,          \
                                                         const std::filesystem::path&);         \
  template void save_nominal_model<N>(const std::filesystem::path&,                             \
                                      const NominalModel<double, N>&, const std::string&,       \
                                      const std::string&);
TPF_INSTANTIATE_NOMINAL_MODEL(1)
TPF_INSTANTIATE_NOMINAL_MODEL(2)
TPF_INSTANTIATE_NOMINAL_MODEL(3)
TPF_INSTANTIATE_NOMINAL_MODEL(4)
TPF_INSTANTIATE_NOMINAL_MODEL(5)
TPF_INSTANTIATE_NOMINAL_MODEL(6)
#undef TPF_INSTANTIATE_NOMINAL_MODEL

}  // namespace tpf
