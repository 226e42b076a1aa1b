#include "arrays.hpp"

#include <string>

namespace tpf::python {

namespace {

std::string shape_text(const InArray& a) {
  std::string text = "(";
  for (py::ssize_t d = 0; d < a.ndim(); ++d)
    text += (d ? ", " : "") + std::to_string(a.shape(d));
  return text + (a.ndim() == 1 ? ",)" : ")");
}

}  // namespace

Samples joint_samples(int width,
                      std::initializer_list<std::pair<const char*, const InArray*>> args) {
  Samples samples;
  bool first = true;
  for (const auto& [name, array] : args) {
    const bool one = array->ndim() == 1 && array->shape(0) == width;
    const bool stacked = array->ndim() == 2 && array->shape(1) == width;
    if (!one && !stacked)
      throw py::value_error(std::string(name) + " has shape " + shape_text(*array) +
                            ", expected (" + std::to_string(width) + ",) or (samples, " +
                            std::to_string(width) + ")");
    const py::ssize_t count = stacked ? array->shape(0) : 1;
    if (!first && (stacked != samples.stacked || count != samples.count))
      throw py::value_error(std::string(name) + " has shape " + shape_text(*array) +
                            ", unlike the arguments before it");
    samples = {count, stacked};
    first = false;
  }
  return samples;
}

OutArray new_output(const Samples& samples, std::vector<py::ssize_t> shape) {
  if (samples.stacked) shape.insert(shape.begin(), samples.count);
  return OutArray(shape);
}

py::array readonly_view(const Eigen::VectorXd& v, py::handle owner) {
  py::array a(py::dtype::of<double>(), {v.size()}, {py::ssize_t(sizeof(double))}, v.data(), owner);
  py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}

py::array readonly_view(const Eigen::MatrixXd& m, py::handle owner) {
  const auto item = py::ssize_t(sizeof(double));
  py::array a(py::dtype::of<double>(), {m.rows(), m.cols()}, {item, item * m.rows()}, m.data(),
              owner);
  py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}

}  // namespace tpf::python
