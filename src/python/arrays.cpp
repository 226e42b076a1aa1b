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
  return joint_samples(width, args.begin(), static_cast<int>(args.size()));
}

Samples joint_samples(int width, const std::pair<const char*, const InArray*>* args, int count) {
  Samples samples;
  bool first = true;
  for (int k = 0; k < count; ++k) {
    const auto& [name, array] = args[k];
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

namespace {

/// numpy's float64 descriptor in native byte order: one object for the process (numpy's own).
PyObject* native_double() {
  static PyObject* const descr =
      py::detail::npy_api::get().PyArray_DescrFromType_(py::detail::npy_api::NPY_DOUBLE_);
  return descr;
}

}  // namespace

double* exact_array(py::handle h, const Shape& shape, bool writable) {
  using api = py::detail::npy_api;
  if (!api::get().PyArray_Check_(h.ptr())) return nullptr;
  const auto* a = py::detail::array_proxy(h.ptr());
  const int needed = api::NPY_ARRAY_C_CONTIGUOUS_ | api::NPY_ARRAY_ALIGNED_ |
                     (writable ? api::NPY_ARRAY_WRITEABLE_ : 0);
  if (a->descr != native_double() || (a->flags & needed) != needed || a->nd != shape.axes)
    return nullptr;
  for (int d = 0; d < shape.axes; ++d)
    if (a->dimensions[d] != shape.extent[d]) return nullptr;
  return reinterpret_cast<double*>(a->data);
}

py::array new_array(const Shape& shape) {
  const auto& api = py::detail::npy_api::get();
  PyObject* descr = native_double();
  Py_INCREF(descr);  // PyArray_NewFromDescr takes a reference to it
  Py_intptr_t dims[4];
  for (int d = 0; d < shape.axes; ++d)
    dims[d] = shape.extent[d];
  PyObject* a = api.PyArray_NewFromDescr_(api.PyArray_Type_, descr, shape.axes, dims, nullptr,
                                          nullptr, 0, nullptr);
  if (!a) throw py::error_already_set();
  return py::reinterpret_steal<py::array>(a);
}

py::object output_array(py::handle out, const Shape& shape, double*& data) {
  if (out.is_none()) {
    py::array a = new_array(shape);
    data = static_cast<double*>(a.mutable_data());
    return a;
  }
  data = exact_array(out, shape, true);
  if (!data) {
    std::string text = "(";
    for (int d = 0; d < shape.axes; ++d)
      text += (d ? ", " : "") + std::to_string(shape.extent[d]);
    throw py::value_error("out must be a writable C-ordered float64 array of shape " + text +
                          (shape.axes == 1 ? ",)" : ")"));
  }
  return py::reinterpret_borrow<py::object>(out);
}

InArray input_array(const char* name, py::handle h) {
  InArray a = InArray::ensure(h);
  if (!a) throw py::type_error(std::string(name) + " must be an array of numbers");
  return a;
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
