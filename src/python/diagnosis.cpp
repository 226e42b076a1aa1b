// tpf.diagnose: what the residual says the declared model lacks, added and checked held out
// (offline/diagnose), with the content of `tpf diagnose --json` and the model of `--params`.
#include <pybind11/stl.h>

#include <string>
#include <utility>

#include "bindings.hpp"
#include "nominal_model.hpp"
#include "offline/diagnose/diagnose.hpp"
#include "offline/diagnose/diagnosis_report.hpp"
#include "offline/log/log_joint_count.hpp"
#include "results.hpp"
#include "tpf/model/load_robot.hpp"

namespace tpf::python {

namespace {

/// What tpf.diagnose returns: the written model and the diagnosis as JSON text.
struct DiagnoseResult {
  Nominal nominal;
  std::string source;
  std::string report;  ///< diagnosis_json
  bool refitted = false;
};

DiagnoseResult diagnose_logs(const py::object& logs, const std::string& robot,
                             double static_velocity, double min_improvement, bool inertia_prior) {
  const LogArgument read(logs, true);
  const offline::Log& log = *read;
  const offline::ModelX model = load_robot<double, Eigen::Dynamic>(robot);
  offline::require_log_joint_count(log.joint_count(), log.source, model.joint_count(), robot,
                                   "give the robot file of the arm that made the log (robot=)");
  if (!(min_improvement >= 0 && min_improvement < 1))
    throw py::value_error("min_improvement must be in [0, 1)");
  offline::DiagnoseOptions options;
  options.samples.regimes.static_velocity = static_velocity;
  options.min_improvement = min_improvement;
  options.inertia_prior = inertia_prior;
  py::gil_scoped_release unlocked;
  offline::Diagnosis d = offline::diagnose(log, model, options);
  std::string report = offline::diagnosis_json(d);
  return {Nominal(std::move(d.nominal)), log.source, std::move(report), d.refitted};
}

}  // namespace

void bind_diagnosis(py::module_& m) {
  py::class_<DiagnoseResult> c(m, "Diagnosis",
                               "tpf.diagnose's result: the written model and the diagnosis.");
  c.def_property_readonly(
       "nominal", [](DiagnoseResult& r) -> Nominal& { return r.nominal; },
       py::return_value_policy::reference_internal,
       "the declared model with the effects claimed (tpf.NominalModel), as `--params` writes it")
      .def_readonly("source", &DiagnoseResult::source, "the log's path(s)")
      .def_readonly("refitted", &DiagnoseResult::refitted,
                    "the written model was refitted on every sample, the held-out ones included")
      .def_property_readonly(
          "report", [](const DiagnoseResult& r) { return python_of_json(r.report); },
          "what `tpf diagnose --json` writes, as dicts and lists")
      .def(
          "save",
          [](const DiagnoseResult& r, const std::string& path) {
            save_nominal_model(path, r.nominal.nominal, r.source, "");
          },
          py::arg("path"), "Writes the parameter file as `tpf diagnose --params` does.");
  m.def("diagnose", &diagnose_logs, py::arg("logs"), py::arg("robot"), py::kw_only(),
        py::arg("static_velocity") = 1e-4, py::arg("min_improvement") = 0.10,
        py::arg("inertia_prior") = true,
        "`tpf diagnose`: fits the declared model of the robot file `robot` on `logs` (a path, a "
        "list of paths read as one, or a tpf.Log), finds the effects the residual holds, adds "
        "those that pass on held-out data and refits. Options as the CLI's.");
}

}  // namespace tpf::python
