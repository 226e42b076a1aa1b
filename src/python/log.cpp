// tpf.Log, tpf.read_log, tpf.write_log: tpf logs (docs/log-format.md) as numpy arrays.
#include <pybind11/stl.h>

#include <algorithm>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "arrays.hpp"
#include "bindings.hpp"
#include "offline/log/log_io.hpp"
#include "robot.hpp"
#include "tpf/model/effort_unit.hpp"

namespace tpf::python {

namespace {

using offline::Log;

/// The columns prefix1..prefixN of the log's N joints as (S, N), or None when the log has none
/// of them (all of them are needed otherwise). Read-only: a view of the log's values when the
/// columns are adjacent in file order, a copy when not.
py::object joint_columns(py::object self, const std::string& prefix) {
  const Log& log = self.cast<const Log&>();
  const int n = log.joint_count();
  if (n == 0 || !log.has(offline::indexed_name(prefix, 1))) return py::none();
  std::vector<int> index;
  for (int j = 1; j <= n; ++j)
    index.push_back(log.column(offline::indexed_name(prefix, j)));  // Log::col names a missing one
  for (int j = 1; j <= n; ++j)
    if (index[j - 1] < 0) (void)log.col(offline::indexed_name(prefix, j));
  const auto rows = static_cast<py::ssize_t>(log.rows());
  const auto item = py::ssize_t(sizeof(double));
  bool adjacent = true;
  for (int j = 1; j < n; ++j)
    adjacent = adjacent && index[j] == index[0] + j;
  py::array out;
  if (adjacent) {
    out = py::array(py::dtype::of<double>(), {rows, py::ssize_t(n)}, {item, item * rows},
                    log.values.col(index[0]).data(), self);
  } else {
    Eigen::MatrixXd copy(log.rows(), n);
    for (int j = 0; j < n; ++j)
      copy.col(j) = log.values.col(index[j]);
    out = py::array(py::dtype::of<double>(), {rows, py::ssize_t(n)}, {item, item * rows},
                    copy.data());
  }
  py::detail::array_proxy(out.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return out;
}

/// Metadata from a dict or a list of (key, value) pairs, in that order.
offline::LogMetadata metadata_of(const py::object& meta) {
  offline::LogMetadata m;
  if (meta.is_none()) return m;
  const py::object items = py::isinstance<py::dict>(meta) ? meta.attr("items")() : meta;
  for (const py::handle item : items) {
    const auto pair = item.cast<std::pair<std::string, std::string>>();
    m.entries.push_back(pair);
  }
  return m;
}

Log log_of(std::vector<std::string> columns, const Eigen::MatrixXd& values,
           const py::object& meta) {
  if (static_cast<Eigen::Index>(columns.size()) != values.cols())
    throw py::value_error(std::to_string(columns.size()) + " column names for " +
                          std::to_string(values.cols()) + " columns of values");
  Log log;
  log.source = "(from Python)";
  log.meta = metadata_of(meta);
  log.columns = std::move(columns);
  log.values = values;
  log.quality.rows = static_cast<std::size_t>(values.rows());
  log.quality.missing_per_column.assign(log.columns.size(), 0);
  return log;
}

/// The effort columns in N·m: tau<j> as they are, i<j> [mA] times K_t/1000 of `robot`.
Eigen::MatrixXd torque_of(const Log& log, const Robot& robot) {
  const std::string prefix = log.effort_prefix();
  const int n = log.joint_count();
  if (n != robot.n())
    throw py::value_error("the log has " + std::to_string(n) + " joints, the robot " +
                          std::to_string(robot.n()));
  Eigen::MatrixXd effort(log.rows(), n);
  for (int j = 0; j < n; ++j)
    effort.col(j) = log.col(offline::indexed_name(prefix, j + 1));
  return drive_units(robot.model, effort_unit_of_column(prefix)).to_torque(effort);
}

void bind_log_columns(py::class_<Log>& c) {
  c.def_property_readonly(
      "t",
      [](py::object self) {
        const Log& log = self.cast<const Log&>();
        const Eigen::Index t = log.column("t");
        if (t < 0) (void)log.col("t");
        const auto item = py::ssize_t(sizeof(double));
        py::array a(py::dtype::of<double>(), {py::ssize_t(log.rows())}, {item},
                    log.values.col(t).data(), self);
        py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
        return a;
      },
      "sample times [s] (S,)");
  for (const char* prefix : {"q", "dq", "ddq", "i", "tau", "tau_sensor"})
    c.def_property_readonly(
        prefix, [prefix](py::object self) { return joint_columns(self, prefix); },
        (std::string("columns ") + prefix + "1..N as (S, N), None when absent").c_str());
  c.def("joints", &joint_columns, py::arg("prefix"),
        "columns <prefix>1..<prefix>N of the N joints as (S, N), None when absent");
  c.def(
      "column",
      [](py::object self, const std::string& name) {
        Log& log = self.cast<Log&>();
        Eigen::Ref<Eigen::VectorXd> col = log.col(name);
        const auto item = py::ssize_t(sizeof(double));
        return py::array(py::dtype::of<double>(), {py::ssize_t(col.size())}, {item}, col.data(),
                         self);
      },
      py::arg("name"), "column `name` as a writable view (S,); tpf.Error when absent");
  c.def("torque", &torque_of, py::arg("robot"),
        "effort columns in N·m (S, N): tau<j>, or i<j> [mA] converted with the robot's K_t");
}

}  // namespace

void bind_log(py::module_& m) {
  py::class_<Log> c(m, "Log", "A tpf log: metadata, named columns, values (samples × columns).");
  c.def(py::init(&log_of), py::arg("columns"), py::arg("values"), py::arg("meta") = py::none(),
        "A log of `values` (S, C) under `columns` (C names), metadata a dict or (key, value) "
        "pairs.")
      .def_readonly("source", &Log::source)
      .def_readonly("columns", &Log::columns)
      .def_property_readonly(
          "values",
          [](py::object self) {
            const Log& log = self.cast<const Log&>();
            const auto item = py::ssize_t(sizeof(double));
            return py::array(py::dtype::of<double>(), {log.values.rows(), log.values.cols()},
                             {item, item * log.values.rows()}, log.values.data(), self);
          },
          "values (S, C), a writable view; missing = NaN")
      .def_property_readonly(
          "meta", [](const Log& log) { return log.meta.entries; },
          "metadata (key, value) pairs in file order (key '' for a comment)")
      .def_property_readonly("rows", &Log::rows)
      .def_property_readonly("joint_count", &Log::joint_count)
      .def_property_readonly("pad_count", &Log::pad_count)
      .def_property_readonly("effort_prefix", &Log::effort_prefix, "'i' (mA) or 'tau' (N·m)")
      .def_property_readonly("rate_hz", [](const Log& log) { return log.quality.rate_hz; })
      .def_property_readonly(
          "gap_rows", [](const Log& log) { return log.quality.gap_rows; },
          "first row after each gap")
      .def_property_readonly(
          "notes", [](const Log& log) { return log.quality.notes; },
          "what the reader left out or doubted, one line each")
      .def_property_readonly("summary",
                             [](const Log& log) { return log.quality.summary(log.columns); })
      .def(
          "write", [](const Log& log, const std::string& path) { offline::write_log(path, log); },
          py::arg("path"), "Writes the log (atomically; gzip for a path ending in .gz).")
      .def("__len__", &Log::rows)
      .def("__repr__", [](const Log& log) {
        return "tpf.Log('" + log.source + "', " + std::to_string(log.rows()) + " rows, " +
               std::to_string(log.columns.size()) + " columns)";
      });
  bind_log_columns(c);
  m.def(
      "read_log",
      [](const std::string& path, const std::optional<std::vector<std::string>>& columns) {
        if (!columns) return offline::read_log(path);
        return offline::read_log(path, [&](std::string_view name) {
          return name == "t" || std::find(columns->begin(), columns->end(), name) != columns->end();
        });
      },
      py::arg("path"), py::arg("columns") = py::none(),
      "Reads a tpf log (.csv or .csv.gz); `columns`: keep only these (and t).");
  m.def(
      "write_log", [](const std::string& path, const Log& log) { offline::write_log(path, log); },
      py::arg("path"), py::arg("log"), "Writes `log` to `path` (atomically).");
}

}  // namespace tpf::python
