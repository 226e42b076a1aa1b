// The offline tools' results for Python: the JSON the CLI writes, as Python dicts and lists, and
// the logs a tool reads, from a path, several paths or a tpf.Log.
#pragma once

#include <pybind11/pybind11.h>

#include <string>

#include "offline/log/log.hpp"

namespace tpf::python {

namespace py = pybind11;

/// The JSON text `json` as Python objects (json.loads): objects as dicts, arrays as lists, null
/// as None — equal to what Python reads from the file the CLI writes.
py::object python_of_json(const std::string& json);

/// The log(s) `logs` names: a path, a list of paths (read as one, each file its own segment, as
/// the CLI's --log given several times) or a tpf.Log (used in place, not copied: the caller's
/// argument keeps it alive). `columns_for_fit`: read only the columns identification and
/// diagnosis use (as `tpf identify` does).
class LogArgument {
 public:
  LogArgument(const py::object& logs, bool columns_for_fit);
  LogArgument(const LogArgument&) = delete;
  LogArgument& operator=(const LogArgument&) = delete;
  const offline::Log& operator*() const { return *log_; }
  const offline::Log* operator->() const { return log_; }

 private:
  offline::Log read_;
  const offline::Log* log_ = &read_;
};

}  // namespace tpf::python
