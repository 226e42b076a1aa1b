// tpf::Error as the Python exception tpf.Error (a RuntimeError) with the file, line and field the
// message names.
#include "tpf/common/error.hpp"

#include <string>
#include <string_view>

#include "bindings.hpp"

namespace tpf::python {

namespace {

namespace py = pybind11;

/// Where an error message says the problem is.
struct ErrorPlace {
  std::string file, field, message;
  long line = 0;
};

/// Splits a message of Error::at's form "<file>[:<line>]: [<field>: ]<message>". A first part
/// with neither '/' nor '.' is not a file name (an error raised without one): the whole text is
/// then the message.
ErrorPlace error_place(std::string_view text) {
  ErrorPlace place;
  place.message = text;
  const auto head_end = text.find(": ");
  if (head_end == std::string_view::npos) return place;
  std::string_view head = text.substr(0, head_end);
  if (head.find_first_of("/.") == std::string_view::npos) return place;
  const auto colon = head.rfind(':');
  if (colon != std::string_view::npos && colon + 1 < head.size() &&
      head.substr(colon + 1).find_first_not_of("0123456789") == std::string_view::npos) {
    place.line = std::stol(std::string(head.substr(colon + 1)));
    head = head.substr(0, colon);
  }
  place.file = head;
  std::string_view rest = text.substr(head_end + 2);
  const auto field_end = rest.find(": ");
  if (field_end != std::string_view::npos) {
    place.field = rest.substr(0, field_end);
    rest = rest.substr(field_end + 2);
  }
  place.message = rest;
  return place;
}

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
      const ErrorPlace place = error_place(e.what());
      py::object error = py::reinterpret_borrow<py::object>(error_type)(e.what());
      error.attr("file") = place.file;
      error.attr("line") = place.line;
      error.attr("field") = place.field;
      error.attr("message") = place.message;
      PyErr_SetObject(error_type, error.ptr());
    }
  });
}

}  // namespace tpf::python
