// numpy arrays of joint-space samples: one sample (n,) or S stacked samples (S, n), the loop over
// the samples in C++.
#pragma once

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <Eigen/Core>
#include <initializer_list>
#include <utility>
#include <vector>

namespace tpf::python {

namespace py = pybind11;

/// A float64 C-ordered array: numpy's own is taken as it is (a view), anything else converted.
using InArray = py::array_t<double, py::array::c_style | py::array::forcecast>;
using OutArray = py::array_t<double>;
using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// How many samples the joint-space arguments of a call hold.
struct Samples {
  py::ssize_t count = 1;
  bool stacked = false;  ///< (S, n) arguments: the outputs are stacked the same way
};

/// Checks that each named argument is (width,) or (S, width), all of one shape. Throws ValueError
/// naming the argument and the shape expected.
Samples joint_samples(int width,
                      std::initializer_list<std::pair<const char*, const InArray*>> args);

/// Sample s of an argument checked by joint_samples.
inline Eigen::Map<const Eigen::VectorXd> sample(const InArray& a, py::ssize_t s, int width) {
  return {a.data() + s * width, width};
}

/// An output of one `shape` per sample: `shape` itself, or (S, shape...) when stacked.
OutArray new_output(const Samples& samples, std::vector<py::ssize_t> shape);

/// The storage of sample s of an output made by new_output, `size` numbers per sample.
inline double* output_sample(OutArray& out, py::ssize_t s, py::ssize_t size) {
  return out.mutable_data() + s * size;
}

/// A read-only numpy view of an Eigen vector or (column-major) matrix that `owner` keeps alive.
py::array readonly_view(const Eigen::VectorXd& v, py::handle owner);
py::array readonly_view(const Eigen::MatrixXd& m, py::handle owner);

}  // namespace tpf::python
