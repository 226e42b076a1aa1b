// tpf.estimate: the run-time estimator (offline/replay: its joints and pads at run time, the
// compensator the weight files hold, the held-out gate) stepped over every sample of a log or of
// arrays, the loop in C++, each per-row quantity returned as a numpy view of the trace.
#include <pybind11/stl.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "arrays.hpp"
#include "bindings.hpp"
#include "offline/replay/replay_estimator.hpp"
#include "results.hpp"
#include "tpf/model/effort_unit.hpp"

namespace tpf::python {

namespace {

using offline::ReplaySample;

/// A (rows,) or (rows, width) array of the dict `arrays` under `key`, as float64 C-ordered.
InArray array_entry(const py::dict& arrays, const char* key, py::ssize_t rows, int width) {
  const InArray a = InArray::ensure(arrays[key]);
  const bool ok = a && (width == 0 ? a.ndim() == 1 && a.shape(0) == rows
                                   : a.ndim() == 2 && a.shape(0) == rows && a.shape(1) == width);
  if (!ok)
    throw py::value_error(std::string(key) + " must be " +
                          (width == 0 ? "(S,)" : "(S, " + std::to_string(width) + ")") +
                          " with S = len(t) = " + std::to_string(rows));
  return a;
}

/// Samples from arrays: t (S,), q, dq (S, n), the effort tau (S, n) [N·m] or i (S, n) [mA],
/// optionally p (S, pads) [kPa] — what estimator_samples reads off a log's columns.
std::vector<ReplaySample> samples_of_arrays(const py::dict& arrays,
                                            const Model<double, Eigen::Dynamic>& model, int pads) {
  const int n = model.joint_count();
  for (const char* key : {"t", "q", "dq"})
    if (!arrays.contains(key)) throw py::value_error(std::string("arrays: no '") + key + "'");
  const bool current = arrays.contains("i");
  if (current == arrays.contains("tau"))
    throw py::value_error("arrays: give the effort as 'tau' [N·m] or as 'i' [mA], one of them");
  const py::ssize_t rows = InArray::ensure(arrays["t"]).size();
  const InArray t = array_entry(arrays, "t", rows, 0), q = array_entry(arrays, "q", rows, n),
                dq = array_entry(arrays, "dq", rows, n),
                effort = array_entry(arrays, current ? "i" : "tau", rows, n);
  const bool pressure = pads > 0 && arrays.contains("p");
  const InArray p = pressure ? array_entry(arrays, "p", rows, pads) : InArray();
  std::vector<ReplaySample> samples(static_cast<std::size_t>(rows));
  for (py::ssize_t r = 0; r < rows; ++r) {
    ReplaySample& s = samples[static_cast<std::size_t>(r)];
    s.resize(n, pads);
    s.t = t.data()[r];
    s.q = sample(q, r, n);
    s.dq = sample(dq, r, n);
    s.effort = sample(effort, r, n);
    if (current) s.effort = torque_from_current(model, s.effort);
    if (pressure) s.pressure = sample(p, r, pads);
  }
  return samples;
}

template <typename Matrix>
py::array trace_view(const Matrix& m, py::handle owner) {
  using Scalar = typename Matrix::Scalar;
  const auto item = py::ssize_t(sizeof(Scalar));
  py::array a = Matrix::ColsAtCompileTime == 1
                    ? py::array(py::dtype::of<Scalar>(), {m.rows()}, {item}, m.data(), owner)
                    : py::array(py::dtype::of<Scalar>(), {m.rows(), m.cols()},
                                {item, item * m.rows()}, m.data(), owner);
  py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}

/// The trace's per-row quantities as read-only views (the trace is kept alive by them).
py::dict trace_arrays(std::unique_ptr<offline::EstimatorTrace> trace) {
  const offline::EstimatorTrace& tr = *trace;
  const py::capsule owner(trace.release(),
                          [](void* p) { delete static_cast<offline::EstimatorTrace*>(p); });
  py::dict d;
  d["t"] = trace_view(tr.t, owner);
  d["dq"] = trace_view(tr.dq, owner);
  d["inputs"] = trace_view(tr.inputs, owner);
  d["residual"] = trace_view(tr.residual, owner);
  d["compensation"] = trace_view(tr.compensation, owner);
  d["static_estimate"] =
      trace_view(tr.estimates[static_cast<int>(TorqueEstimator::StaticModelFree)], owner);
  d["fused_estimate"] = trace_view(tr.estimates[static_cast<int>(TorqueEstimator::Fused)], owner);
  d["proprioceptive"] = trace_view(tr.proprioceptive, owner);
  d["external"] = trace_view(tr.external, owner);
  d["state"] = trace_view(tr.state, owner);
  d["contact"] = trace_view(tr.contact, owner);
  d["estimator_contact"] = trace_view(tr.estimator_contact, owner);
  d["pad"] = trace_view(tr.pad, owner);
  d["pad_force"] = trace_view(tr.pad_force, owner);
  d["force_world"] = trace_view(tr.force_world, owner);
  d["wrench_valid"] = trace_view(tr.wrench_valid, owner);
  d["force_tactile"] = trace_view(tr.force_tactile, owner);
  d["force_proprioceptive"] = trace_view(tr.force_proprioceptive, owner);
  d["torque_tactile"] = trace_view(tr.torque_tactile, owner);
  return d;
}

py::dict estimate(const py::object& data, const std::string& params, const std::string& robot,
                  const std::optional<std::string>& estimator,
                  const std::optional<std::string>& weights,
                  const std::optional<std::string>& pads) {
  EstimatorFiles files{params, robot, pads.value_or(""), estimator.value_or(""),
                       weights.value_or("")};
  const offline::ReplaySetup setup = load_estimator_setup(files);
  const int pad_count = static_cast<int>(setup.pads.size());
  const std::vector<ReplaySample> samples =
      py::isinstance<py::dict>(data)
          ? samples_of_arrays(data.cast<py::dict>(), setup.nominal.model, pad_count)
          : offline::estimator_samples(*LogArgument(data, false), setup.nominal.model, pad_count);
  auto trace = std::make_unique<offline::EstimatorTrace>();
  {
    py::gil_scoped_release unlocked;
    *trace = offline::replay_estimator(setup, samples);
  }
  return trace_arrays(std::move(trace));
}

}  // namespace

void bind_estimate(py::module_& m) {
  m.def("estimate", &estimate, py::arg("data"), py::arg("params"), py::arg("robot"), py::kw_only(),
        py::arg("estimator") = py::none(), py::arg("weights") = py::none(),
        py::arg("pads") = py::none(),
        "The run-time estimator over every sample of `data`: a tpf.Log, a log's path, or a dict "
        "of arrays t (S,), q, dq (S, n), tau (S, n) [N·m] or i (S, n) [mA], p (S, pads) [kPa]. "
        "Built from the parameter file `params` for `robot`, the estimator parameters "
        "`estimator` (default: the defaults), compensator `weights` (held-out gate applied) and "
        "pad layout `pads` (None: no skin). Returns a dict of read-only (S,) / (S, n) arrays: "
        "residual, compensation, static_estimate, fused_estimate, proprioceptive, external "
        "[N·m], state (0 static-free, 1 static-contact, 2 dynamic), contact, "
        "estimator_contact, pad, pad_force, force_world, wrench_valid, inputs, dq, t; NaN (-1) "
        "on rows the estimator skipped.");
}

}  // namespace tpf::python
