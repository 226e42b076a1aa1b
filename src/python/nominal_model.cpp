// tpf.NominalModel: a parameter file (identified rigid body, friction, added effects) and the
// effort it predicts over numpy samples.
#include "nominal_model.hpp"

#include <pybind11/stl.h>

#include <string>
#include <vector>

#include "bindings.hpp"
#include "friction.hpp"
#include "robot.hpp"
#include "tpf/estimation/nominal_model.hpp"

namespace tpf::python {

namespace {

/// predict_effort over samples: (rigid, friction), each (n,) or (S, n) [N·m].
py::tuple predict(Nominal& m, const InArray& q, const InArray& dq, const InArray& ddq) {
  const int n = m.n();
  const Samples samples = joint_samples(n, {{"q", &q}, {"dq", &dq}, {"ddq", &ddq}});
  OutArray rigid = new_output(samples, {n}), friction = new_output(samples, {n});
  for (py::ssize_t s = 0; s < samples.count; ++s) {
    m.q = sample(q, s, n);
    m.dq = sample(dq, s, n);
    m.ddq = sample(ddq, s, n);
    predict_effort(m.nominal, m.links, m.data, m.q, m.dq, m.ddq, m.rigid, m.friction);
    Eigen::Map<Eigen::VectorXd>(output_sample(rigid, s, n), n) = m.rigid;
    Eigen::Map<Eigen::VectorXd>(output_sample(friction, s, n), n) = m.friction;
  }
  return py::make_tuple(rigid, friction);
}

std::vector<std::string> base_names(const Nominal& m) {
  std::vector<std::string> names;
  for (int i = 0; i < m.nominal.base_count; ++i)
    names.push_back(regressor_column_name(m.n(), m.nominal.base_columns[i]));
  return names;
}

}  // namespace

void bind_nominal_model(py::module_& m) {
  py::class_<Nominal> c(m, "NominalModel",
                        "An identified model (parameter file, torques in N·m): rigid body in "
                        "base parameters, friction, added effects.");
  c.def_property_readonly("joint_count", &Nominal::n)
      .def_property_readonly("robot", [](const Nominal& n) { return Robot(n.nominal.model); })
      .def_property_readonly("base_count", [](const Nominal& n) { return n.nominal.base_count; })
      .def_property_readonly(
          "base_columns",
          [](const Nominal& n) {
            return std::vector<int>(n.nominal.base_columns.begin(),
                                    n.nominal.base_columns.begin() + n.nominal.base_count);
          },
          "regressor columns of the base parameters (Robot.compute_regressor)")
      .def_property_readonly("base_names", &base_names,
                             "names of the base parameters (regressor columns, e.g. 'mx3')")
      .def_property_readonly(
          "base_values",
          [](const Nominal& n) {
            return Eigen::VectorXd(n.nominal.base_values.head(n.nominal.base_count));
          },
          "values of the base parameters (SI)")
      .def_property_readonly("friction",
                             [](const Nominal& n) { return Stribeck(n.nominal.friction); })
      .def("predict_effort", &predict, py::arg("q"), py::arg("dq"), py::arg("ddq"),
           "Predicted joint effort [N·m] split (rigid, friction): rigid = base-parameter rigid "
           "body + added effects, friction = Stribeck with load dependence. Arguments (n,) or "
           "(S, n).")
      .def(
          "save",
          [](const Nominal& n, const std::string& path, const std::string& source) {
            save_nominal_model(path, n.nominal, source);
          },
          py::arg("path"), py::arg("source") = "", "Writes the parameter file (atomically).");
  m.def(
      "load_nominal_model",
      [](const std::string& params, const std::string& robot) {
        return Nominal(load_nominal_model(params, robot));
      },
      py::arg("params"), py::arg("robot"),
      "Reads a parameter file written by `tpf identify` / `tpf diagnose` for the robot file "
      "`robot`.");
}

}  // namespace tpf::python
