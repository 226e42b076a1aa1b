// tpf.validate: a nominal model (and a friction compensator) scored on held-out logs
// (offline/validate), the content of `tpf validate --json` as Python objects.
#include "offline/validate/validation.hpp"

#include <pybind11/stl.h>

#include <optional>
#include <string>
#include <vector>

#include "bindings.hpp"
#include "nominal_model.hpp"
#include "results.hpp"
#include "tpf/estimation/estimator_parameter_file.hpp"

namespace tpf::python {

namespace {

/// The model `params` names: a tpf.NominalModel, or a parameter file read for `robot`.
NominalModelX nominal_argument(const py::object& params, const std::optional<std::string>& robot) {
  if (py::isinstance<Nominal>(params)) return params.cast<const Nominal&>().nominal;
  if (!robot) throw py::value_error("robot: needed with a parameter file's path");
  return load_nominal_model(py::str(params).cast<std::string>(), *robot);
}

py::object validate_logs(const py::object& params, const py::object& logs,
                         const std::optional<std::string>& robot,
                         const std::optional<std::string>& weights,
                         const std::optional<std::string>& estimator, double static_velocity) {
  using namespace offline;
  const NominalModelX nominal = nominal_argument(params, robot);
  const LogArgument read(logs, false);
  const Log& log = *read;
  const int joints = nominal.model.joint_count();
  if (log.joint_count() != joints)
    throw Error::at(log.source, 0, "",
                    "the log has " + std::to_string(log.joint_count()) + " joints, the model " +
                        std::to_string(joints));
  SampleOptions options;
  options.regimes.static_velocity = static_velocity;
  std::string json;
  {
    py::gil_scoped_release unlocked;
    const JointSamples samples = extract_joint_samples(log, nominal.model.torque_constant, options);
    std::vector<std::string> notes;
    std::vector<EffortEstimate> estimates{nominal_estimate(nominal, samples, notes)};
    if (weights) {
      EstimatorSetup<Eigen::Dynamic> setup;
      setup.nominal = nominal;
      if (estimator)
        setup.parameters = load_estimator_parameters(*estimator, joints);
      else
        setup.parameters.resize(joints);
      setup.weights = find_compensator_weights(*weights, joints);
      estimates.push_back(compensated_estimate(setup, log, estimates.front()));
    }
    Validation v = score_estimates(log, samples, estimates);
    v.notes = notes;
    json = validation_json(v);
  }
  return python_of_json(json);
}

}  // namespace

void bind_validation(py::module_& m) {
  m.def("validate", &validate_logs, py::arg("params"), py::arg("logs"), py::kw_only(),
        py::arg("robot") = py::none(), py::arg("weights") = py::none(),
        py::arg("estimator") = py::none(), py::arg("static_velocity") = 1e-4,
        "`tpf validate`: the model `params` (a tpf.NominalModel, or a parameter file with "
        "`robot`) scored on `logs` (a path, a list of paths, or a tpf.Log), all held out; "
        "`weights` adds the compensated column (`estimator`: its parameter file). Returns what "
        "`tpf validate --json` writes, as dicts and lists.");
}

}  // namespace tpf::python
