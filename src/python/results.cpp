#include "results.hpp"

#include <pybind11/stl.h>

#include <string>
#include <vector>

#include "offline/identify/identify.hpp"
#include "offline/log/read_logs.hpp"

namespace tpf::python {

py::object python_of_json(const std::string& json) {
  return py::module_::import("json").attr("loads")(json);
}

LogArgument::LogArgument(const py::object& logs, bool columns_for_fit) {
  if (py::isinstance<offline::Log>(logs)) {
    log_ = &logs.cast<const offline::Log&>();
    return;
  }
  std::vector<std::string> paths;
  if (py::isinstance<py::str>(logs) || py::hasattr(logs, "__fspath__"))
    paths.push_back(py::str(logs).cast<std::string>());
  else
    for (const py::handle p : logs)
      paths.push_back(py::str(p).cast<std::string>());
  if (paths.empty()) throw py::value_error("no log given");
  read_ = offline::read_logs(paths, nullptr,
                             columns_for_fit ? offline::identification_column : nullptr);
}

}  // namespace tpf::python
