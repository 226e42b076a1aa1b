// The parts of the Python module tpf, one function per part (module.cpp calls them in order).
#pragma once

#include <pybind11/pybind11.h>

namespace tpf::python {

void bind_error(pybind11::module_& m);
void bind_robot(pybind11::module_& m);
void bind_friction(pybind11::module_& m);
void bind_nominal_model(pybind11::module_& m);
void bind_log(pybind11::module_& m);
void bind_identification(pybind11::module_& m);
void bind_validation(pybind11::module_& m);
void bind_diagnosis(pybind11::module_& m);
void bind_training(pybind11::module_& m);
void bind_estimate(pybind11::module_& m);

}  // namespace tpf::python
