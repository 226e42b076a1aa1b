#include "offline/upgrade/upgrade_files.hpp"

#include <cmath>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/common/atomic_file.hpp"
#include "tpf/common/error.hpp"
#include "tpf/estimation/compensator.hpp"
#include "tpf/estimation/compensator_weight_files.hpp"

namespace tpf::offline {
namespace {

using Json = nlohmann::ordered_json;

Json read_json(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw Error::at(path.string(), 0, "", "cannot be read");
  std::stringstream text;
  text << in.rdbuf();
  try {
    return Json::parse(text.str());
  } catch (const nlohmann::json::exception& e) {
    throw Error::at(path.string(), 0, "", std::string("not JSON: ") + e.what());
  }
}

/// The file's "format" and "version", checked: `format` and a version in [lowest, highest].
int old_version(const Json& j, const std::filesystem::path& path, const std::string& format,
                int lowest, int highest, const std::string& why_not) {
  if (!j.is_object() || j.value("format", std::string()) != format)
    throw Error::at(path.string(), 0, "format", "is not '" + format + "'");
  if (!j.contains("version") || !j["version"].is_number_integer())
    throw Error::at(path.string(), 0, "version", "missing");
  const int version = j["version"].get<int>();
  if (version < lowest || version > highest)
    throw Error::at(path.string(), 0, "version", "is " + std::to_string(version) + ": " + why_not);
  return version;
}

/// Divides element j of the array at `key` of `object` by k[j] (absent key: nothing to do).
void divide_vector(Json& object, const std::string& key, const std::vector<double>& k,
                   const std::filesystem::path& path, const std::string& field) {
  if (!object.contains(key)) return;
  Json& a = object[key];
  if (!a.is_array() || a.size() != k.size())
    throw Error::at(path.string(), 0, field + key,
                    "must be an array of " + std::to_string(k.size()) + " numbers");
  for (std::size_t j = 0; j < k.size(); ++j) {
    if (!a[j].is_number()) throw Error::at(path.string(), 0, field + key, "must hold numbers");
    a[j] = a[j].get<double>() / k[j];
  }
}

/// Divides row j of the matrix at `key` by k[j]: row j is joint j's torque.
void divide_rows(Json& object, const std::string& key, const std::vector<double>& k,
                 const std::filesystem::path& path, const std::string& field) {
  if (!object.contains(key)) return;
  Json& m = object[key];
  if (!m.is_array() || m.size() != k.size())
    throw Error::at(path.string(), 0, field + key,
                    "must be a " + std::to_string(k.size()) + "-row matrix");
  for (std::size_t j = 0; j < k.size(); ++j) {
    if (!m[j].is_array()) throw Error::at(path.string(), 0, field + key, "must hold rows");
    for (auto& v : m[j]) {
      if (!v.is_number()) throw Error::at(path.string(), 0, field + key, "must hold numbers");
      v = v.get<double>() / k[j];
    }
  }
}

/// Version-1 parameter file → version 2; `k` receives its effort_per_newton_metre.
Json upgrade_params(const std::filesystem::path& path, std::vector<double>& k) {
  Json j = read_json(path);
  old_version(j, path, "tpf-params", 1, 1, "only version 1 (efforts in the log's unit) converts");
  if (!j.contains("effort_per_newton_metre") || !j["effort_per_newton_metre"].is_array())
    throw Error::at(path.string(), 0, "effort_per_newton_metre", "missing");
  for (const auto& v : j["effort_per_newton_metre"]) {
    if (!v.is_number() || !(v.get<double>() > 0) || !std::isfinite(v.get<double>()))
      throw Error::at(path.string(), 0, "effort_per_newton_metre", "must hold positive numbers");
    k.push_back(v.get<double>());
  }
  if (j.contains("friction")) {
    Json& f = j["friction"];
    for (const char* key : {"coulomb", "static", "viscous", "load_coulomb", "load_viscous",
                            "coulomb_asymmetry", "viscous_asymmetry"})
      divide_vector(f, key, k, path, "friction.");
    for (const char* key : {"neighbour_load_coulomb", "neighbour_load_viscous"})
      divide_rows(f, key, k, path, "friction.");
  }
  // The fields a version-1 file can hold are a closed set (what tpf wrote before version 2):
  // effects registered since (tpf/effects/added_effects.hpp) are born in N·m.
  if (j.contains("added_effects")) {
    Json& a = j["added_effects"];
    for (const char* key : {"spring_stiffness", "offset", "spring_offset", "thermal_viscous"})
      divide_vector(a, key, k, path, "added_effects.");
    for (const char* key : {"coupling_velocity", "coupling_acceleration"})
      divide_rows(a, key, k, path, "added_effects.");
    if (a.contains("ripple"))
      for (Json& r : a["ripple"]) {
        const int joint = r.value("joint", 0);
        if (joint < 1 || joint > static_cast<int>(k.size()))
          throw Error::at(path.string(), 0, "added_effects.ripple.joint", "out of range");
        for (const char* key : {"sin", "cos"})
          if (r.contains(key))
            r[key] = r[key].get<double>() / k[static_cast<std::size_t>(joint - 1)];
      }
  }
  j.erase("effort_per_newton_metre");
  j.erase("effort_unit");
  j["version"] = 2;
  j["torque_unit"] = "N*m";
  return j;
}

/// Version-2 estimator parameter file → version 3 (σ's and dead bands divided by k).
Json upgrade_estimator(const std::filesystem::path& path, const std::vector<double>& k) {
  Json j = read_json(path);
  old_version(j, path, "tpf-estimator", 2, 2,
              "only version 2 converts (version 1 lacks the compensator's acceleration domain: "
              "calibrate again)");
  for (const char* key : {"nominal_sigma", "fused_sigma", "static_dead_band"})
    divide_vector(j, key, k, path, "");
  j["version"] = 3;
  j["torque_unit"] = "N*m";
  return j;
}

/// Version-1 weight file of a compensator → version 2: the normalisation of the torque inputs
/// (τ̂_fric,s, τ_fric,nom) and both heads divided by k of their joint. `joint` ≥ 0: a per-joint
/// network (5 inputs, 1 output); −1: one network for all joints (5N inputs, N outputs).
Json upgrade_weights(const std::filesystem::path& path, const std::vector<double>& k, int joint) {
  Json j = read_json(path);
  old_version(j, path, "tpf-tcn-weights", 1, 1,
              "only version 1 (efforts in the log's unit) converts");
  const int n = static_cast<int>(k.size());
  const int outputs = joint >= 0 ? 1 : n;
  const int inputs = kCompensatorInputsPerJoint * outputs;
  const auto joint_of = [&](int o) { return static_cast<std::size_t>(joint >= 0 ? joint : o); };
  if (j["architecture"].value("inputs", 0) != inputs ||
      j["architecture"].value("outputs", 0) != outputs)
    throw Error::at(path.string(), 0, "architecture",
                    "not a compensator of " + std::to_string(inputs) + " inputs and " +
                        std::to_string(outputs) + " outputs");
  for (const char* key : {"mean", "std"}) {
    Json& v = j["normalisation"][key];
    if (!v.is_array() || static_cast<int>(v.size()) != inputs)
      throw Error::at(path.string(), 0, std::string("normalisation.") + key, "wrong size");
    for (int o = 0; o < outputs; ++o)
      for (int channel : {3, 4}) {  // τ̂_fric,s and τ_fric,nom (compensator_input)
        Json& x = v[static_cast<std::size_t>(channel * outputs + o)];
        x = x.get<double>() / k[joint_of(o)];
      }
  }
  for (const char* head : {"head_low", "head_high"}) {
    Json& w = j["tensors"][std::string(head) + ".weight"]["values"];
    Json& b = j["tensors"][std::string(head) + ".bias"]["values"];
    if (!w.is_array() || !b.is_array() || static_cast<int>(b.size()) != outputs ||
        w.size() % static_cast<std::size_t>(outputs) != 0)
      throw Error::at(path.string(), 0, std::string("tensors.") + head, "wrong shape");
    const std::size_t hidden = w.size() / static_cast<std::size_t>(outputs);
    for (int o = 0; o < outputs; ++o) {
      const double kj = k[joint_of(o)];
      for (std::size_t h = 0; h < hidden; ++h) {
        Json& x = w[static_cast<std::size_t>(o) * hidden + h];
        x = x.get<double>() / kj;
      }
      b[static_cast<std::size_t>(o)] = b[static_cast<std::size_t>(o)].get<double>() / kj;
    }
  }
  j["version"] = 2;
  return j;
}

/// `convert(path)`, with a JSON type error (a string where a number belongs, a null) named by
/// the file instead of nlohmann's bare "[json.exception.type_error.302] …".
template <class Convert>
Json naming_the_file(const std::filesystem::path& path, Convert&& convert) {
  try {
    return convert(path);
  } catch (const Json::exception& e) {
    throw Error::at(
        path.string(), 0, "",
        std::string("a field has the wrong type, nothing was converted (") + e.what() + ")");
  }
}

}  // namespace

std::vector<std::string> upgrade_files(const UpgradeFiles& files) {
  std::vector<double> k;
  std::vector<std::pair<std::filesystem::path, Json>> out;
  Json params = naming_the_file(files.params, [&](const auto& p) { return upgrade_params(p, k); });
  if (!files.estimator.empty())
    out.emplace_back(files.estimator, naming_the_file(files.estimator, [&](const auto& p) {
                       return upgrade_estimator(p, k);
                     }));
  if (!files.weights.empty()) {
    const int n = static_cast<int>(k.size());
    if (std::filesystem::exists(files.weights)) {
      out.emplace_back(files.weights, naming_the_file(files.weights, [&](const auto& p) {
                         return upgrade_weights(p, k, -1);
                       }));
    } else {
      for (int j = 0; j < n; ++j) {
        const auto p = joint_weight_path(files.weights, j);
        if (!std::filesystem::exists(p))
          throw Error::at(files.weights.string(), 0, "",
                          "neither the file nor " + p.string() + " exists");
        out.emplace_back(
            p, naming_the_file(p, [&](const auto& q) { return upgrade_weights(q, k, j); }));
      }
    }
  }
  out.emplace_back(files.params, std::move(params));  // last: it holds the factor
  // Every file is written to its temporary before any is renamed into place: a write that fails
  // (a full disk) leaves every file as it was, so the set is converted whole or not at all.
  std::vector<std::unique_ptr<AtomicFile>> staged;
  std::vector<std::string> lines;
  for (const auto& [path, json] : out) {
    staged.push_back(std::make_unique<AtomicFile>(path));
    staged.back()->write(json.dump(json.contains("tensors") ? 1 : 2) + "\n");
    lines.push_back(path.string() + ": version " + std::to_string(json["version"].get<int>()) +
                    ", torques in N*m");
  }
  for (const auto& file : staged)
    file->commit();
  return lines;
}

}  // namespace tpf::offline
