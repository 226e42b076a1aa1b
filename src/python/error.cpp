// tpf::Error as the Python exception tpf.Error (a RuntimeError) with the file, line and field it
// carries.
#include "tpf/common/error.hpp"

#include "bindings.hpp"

namespace tpf::python {

namespace {

namespace py = pybind11;

/// The Python class tpf.Error (set once at import; the module keeps it alive).
PyObject* error_type = nullptr;

}  // namespace

void bind_error(py::module_& m) {
  static py::exception<Error> type(m, "Error", PyExc_RuntimeError);
  type.doc() =
      "An error tpf reports: str(e) is the whole message; e.file, e.line (0: none), e.field and "
      "e.message its parts.";
  error_type = type.ptr();
  py::register_exception_translator([](std::exception_ptr thrown) {
    try {
      if (thrown) std::rethrow_exception(thrown);
    } catch (const Error& e) {
      py::object error = py::reinterpret_borrow<py::object>(error_type)(e.what());
      error.attr("file") = e.file();
      error.attr("line") = e.line();
      error.attr("field") = e.field();
      error.attr("message") = e.message();
      PyErr_SetObject(error_type, error.ptr());
    }
  });
}

}  // namespace tpf::python
