// The Python module tpf: the core at a run-time joint count, friction, the nominal model, tpf logs,
// the run-time estimator and the offline tools' fits, numpy in and numpy out (docs/python.md).
#include "bindings.hpp"

PYBIND11_MODULE(tpf, m) {
  m.doc() =
      "tpf: robot dynamics, friction, nominal model, tpf logs, the run-time estimator over logs, "
      "identify, diagnose, validate and train (docs/python.md)";
  tpf::python::bind_error(m);
  tpf::python::bind_robot(m);
  tpf::python::bind_friction(m);
  tpf::python::bind_nominal_model(m);
  tpf::python::bind_log(m);
  tpf::python::bind_identification(m);
  tpf::python::bind_validation(m);
  tpf::python::bind_diagnosis(m);
  tpf::python::bind_training(m);
  tpf::python::bind_estimate(m);
}
