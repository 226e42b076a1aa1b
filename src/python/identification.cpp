// tpf.identify: the nominal model of an arm from logs (offline/identify), with the fit quality the
// parameter file of `tpf identify --out` holds, as Python objects.
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>

#include "bindings.hpp"
#include "nominal_model.hpp"
#include "offline/identify/identify.hpp"
#include "offline/log/log_joint_count.hpp"
#include "offline/log/unit_check.hpp"
#include "offline/samples/sample_unit_check.hpp"
#include "results.hpp"
#include "tpf/dynamics/rnea.hpp"
#include "tpf/model/load_robot.hpp"

namespace tpf::python {

namespace {

using nlohmann::json;

/// What tpf.identify returns: the model, the fit quality and the residual it was judged on.
struct IdentifyResult {
  Nominal nominal;
  std::string source;
  std::string fit;  ///< the parameter file's "fit", JSON text
  bool refitted = false;
  Eigen::MatrixXd residual;
};

json number_or_null(double x) {
  return std::isfinite(x) ? json(x) : json(nullptr);
}

json log_checks_json(const offline::LogChecks& checks) {
  json rest = json::array();
  for (const double f : checks.rest_factor)
    rest.push_back(number_or_null(f));
  return {{"problems", checks.problems},
          {"notes", checks.notes},
          {"dead_joints", checks.dead_joints},
          {"rest_factor", rest}};
}

json inertia_prior_json(const offline::Identification::InertiaPrior& prior) {
  if (!(prior.floor > 0))
    return {{"applied", false}, {"robot_file_min_mass_eigenvalue", 10 * prior.floor}};
  json candidates = json::array();
  for (const auto& c : prior.candidates)
    candidates.push_back({{"strength", c.strength},
                          {"heldout_error", number_or_null(c.heldout_error)},
                          {"min_mass_eigenvalue", c.min_eigenvalue},
                          {"positive_definite", c.positive_definite}});
  return {{"judged_strength", prior.judged_strength},
          {"written_strength", prior.written_strength},
          {"judged_min_mass_eigenvalue_without", prior.judged_min_eigenvalue},
          {"written_min_mass_eigenvalue_without", prior.written_min_eigenvalue},
          {"floor", prior.floor},
          {"choice", prior.choice},
          {"candidates", candidates}};
}

/// The parameter file's "fit" as `tpf identify` writes it (src/cli/identification_printout.hpp).
json fit_json(const offline::Identification& id, const offline::SampleOptions& options,
              const offline::LogChecks& checks) {
  using offline::Regime;
  json fit;
  for (int j = 0; j < id.samples.joints(); ++j) {
    const auto& h = id.heldout[j];
    fit["heldout_rmse"].push_back({{"static", h[Regime::Static].rmse},
                                   {"static-to-kinetic", h[Regime::StaticToKinetic].rmse},
                                   {"moving", h[Regime::Moving].rmse},
                                   {"all", h.valid.rmse}});
  }
  fit["log_checks"] = log_checks_json(checks);
  const auto& prior = id.inertia_prior;
  if (prior.asked &&
      (!(prior.floor > 0) || prior.judged_strength != 0 || prior.written_strength != 0))
    fit["inertia_prior"] = inertia_prior_json(prior);
  fit["friction_notes"] = id.friction_notes;
  const std::string held_out_note = offline::nothing_held_out_note(id.samples, options);
  if (!held_out_note.empty()) fit["heldout_note"] = held_out_note;
  fit["consistent"] = id.consistency.consistent();
  fit["problems"] = id.consistency.problems;
  fit["simulated"] = id.samples.simulated;
  return fit;
}

IdentifyResult identify_logs(const py::object& logs, const std::string& robot,
                             double static_velocity, bool load_friction, bool friction_from_sensor,
                             bool inertia_prior, bool hold_out) {
  const LogArgument read(logs, true);
  const offline::Log& log = *read;
  const offline::ModelX model = load_robot<double, Eigen::Dynamic>(robot);
  offline::require_log_joint_count(log.joint_count(), log.source, model.joint_count(), robot,
                                   "give the robot file of the arm that made the log (robot=)");
  offline::IdentifyOptions options;
  options.samples.regimes.static_velocity = static_velocity;
  options.samples.hold_out = hold_out;
  options.fit_load_friction = load_friction;
  options.friction_from_sensor = friction_from_sensor;
  options.inertia_prior = inertia_prior;
  offline::Identification id;
  {
    py::gil_scoped_release unlocked;  // minutes on long logs: other Python threads may run
    id = offline::identify(log, model, options);
  }
  const json fit = fit_json(id, options.samples, offline::check_sample_units(model, id.samples));
  return {Nominal(std::move(id.nominal)), log.source, fit.dump(), id.refitted,
          std::move(id.residual)};
}

}  // namespace

void bind_identification(py::module_& m) {
  py::class_<IdentifyResult> c(
      m, "Identification",
      "tpf.identify's result: the nominal model, the fit quality the parameter file keeps under "
      "'fit', and the residual the held-out figures score.");
  c.def_property_readonly(
       "nominal", [](IdentifyResult& r) -> Nominal& { return r.nominal; },
       py::return_value_policy::reference_internal,
       "the identified model (tpf.NominalModel), refitted on every sample where rows were held out")
      .def_readonly("source", &IdentifyResult::source, "the log's path(s)")
      .def_property_readonly(
          "fit", [](const IdentifyResult& r) { return python_of_json(r.fit); },
          "the parameter file's 'fit' as `tpf identify` writes it: heldout_rmse [N·m] per joint "
          "and regime, log_checks, inertia_prior, friction_notes, consistent, problems, simulated")
      .def_readonly("refitted", &IdentifyResult::refitted,
                    "the model was refitted on every sample, the held-out ones included")
      .def_property_readonly(
          "residual",
          [](py::object self) {
            const Eigen::MatrixXd& r = self.cast<const IdentifyResult&>().residual;
            return readonly_view(r, self);
          },
          "effort − prediction of the fit on the training rows (samples, joints) [N·m], NaN "
          "where invalid")
      .def(
          "save",
          [](const IdentifyResult& r, const std::string& path) {
            save_nominal_model(path, r.nominal.nominal, r.source, r.fit);
          },
          py::arg("path"), "Writes the parameter file as `tpf identify --out` does.");
  m.def("identify", &identify_logs, py::arg("logs"), py::arg("robot"), py::kw_only(),
        py::arg("static_velocity") = 1e-4, py::arg("load_friction") = true,
        py::arg("friction_from_sensor") = false, py::arg("inertia_prior") = true,
        py::arg("hold_out") = true,
        "`tpf identify`: the nominal model of the robot file `robot` from `logs` (a path, a list "
        "of paths read as one, or a tpf.Log). Options as the CLI's: static_velocity [rad/s], "
        "load_friction (False: --no-load-friction), friction_from_sensor, inertia_prior; "
        "hold_out=False fits every sample (the caller scores on other logs).");
}

}  // namespace tpf::python
