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
Samples joint_samples(int width, const std::pair<const char*, const InArray*>* args, int count);

/// `h` as a float64 C-ordered array: a view of numpy's own, else converted. TypeError naming
/// `name` when it cannot be.
InArray input_array(const char* name, py::handle h);

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

/// The shape of an array of at most 4 axes, without allocation.
struct Shape {
  py::ssize_t extent[4] = {};
  int axes = 0;

  Shape(std::initializer_list<py::ssize_t> extents) {
    for (const py::ssize_t e : extents)
      extent[axes++] = e;
  }
  /// The shape of S samples of this one: (S, extent...).
  Shape stacked(py::ssize_t samples) const {
    Shape s{samples};
    for (int d = 0; d < axes; ++d)
      s.extent[s.axes++] = extent[d];
    return s;
  }
  py::ssize_t size() const {
    py::ssize_t n = 1;
    for (int d = 0; d < axes; ++d)
      n *= extent[d];
    return n;
  }
};

/// The numbers of `h` when it is a numpy array of float64 in native byte order, C-contiguous and
/// aligned, of `shape` (and writable when `writable`): read or written in place, no reference
/// taken. nullptr for anything else (the caller converts it, or refuses it).
double* exact_array(py::handle h, const Shape& shape, bool writable = false);

/// A new C-ordered float64 array of `shape`, uninitialised.
py::array new_array(const Shape& shape);

/// The array results go to: `out` when it is not None (it must be exact_array of `shape`,
/// writable; ValueError otherwise), else a new one. `data` gets its numbers.
py::object output_array(py::handle out, const Shape& shape, double*& data);

/// A read-only numpy view of an Eigen vector or (column-major) matrix that `owner` keeps alive.
py::array readonly_view(const Eigen::VectorXd& v, py::handle owner);
py::array readonly_view(const Eigen::MatrixXd& m, py::handle owner);

}  // namespace tpf::python
