// tpf.train: the friction compensator trained on contact-free logs as `tpf train` trains it
// (offline/compensator_training): the logs split into training and held-out data, the
// estimator's traces, the networks, the weight files with their held-out gains.
#include <pybind11/stl.h>

#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "arrays.hpp"
#include "bindings.hpp"
#include "offline/compensator_training/held_out_score.hpp"
#include "offline/compensator_training/train_compensator.hpp"
#include "offline/log/read_log.hpp"
#include "offline/replay/replay_estimator.hpp"
#include "results.hpp"
#include "tpf/estimation/compensator_weight_files.hpp"
#include "tpf/estimation/nominal_model.hpp"
#include "tpf/model/robot_description.hpp"

namespace tpf::python {

namespace {

using offline::Log;

/// Share of a single log's rows held out (its last time block), as `tpf train`.
constexpr double kTrainHeldOutShare = 0.2;

/// The logs split as `tpf train` splits them: the last file held out when the others hold at
/// least 80 % of the rows, else the last 20 % of the last log's rows.
std::pair<std::vector<Log>, std::vector<Log>> split_training_logs(std::vector<Log> training) {
  std::vector<Log> held_out;
  Eigen::Index others = 0;
  for (std::size_t i = 0; i + 1 < training.size(); ++i)
    others += training[i].rows();
  if (training.size() > 1 && double(others) >= (1.0 - kTrainHeldOutShare) / kTrainHeldOutShare *
                                                   double(training.back().rows())) {
    held_out.push_back(std::move(training.back()));
    training.pop_back();
    return {std::move(training), std::move(held_out)};
  }
  Log& whole = training.back();
  const Eigen::Index rows = whole.rows();
  const Eigen::Index cut = rows - static_cast<Eigen::Index>(kTrainHeldOutShare * double(rows));
  Log tail = whole;
  tail.values = whole.values.bottomRows(rows - cut).eval();
  tail.file_starts = {0};
  tail.source = whole.source + " (last 20 %)";
  whole.values.conservativeResize(cut, Eigen::NoChange);
  held_out.push_back(std::move(tail));
  return {std::move(training), std::move(held_out)};
}

/// The estimator's trace over each log (no skin, the compensator of `weights`), its parameters
/// from each log's own noise, as `tpf train` replays them.
std::vector<offline::EstimatorTrace> training_traces(const NominalModelX& nominal,
                                                     const std::vector<Log>& logs,
                                                     const CompensatorWeightFiles& weights = {}) {
  offline::ReplaySetup setup;
  setup.nominal = nominal;
  setup.weights = weights;
  std::vector<offline::EstimatorTrace> traces;
  for (const Log& log : logs) {
    std::vector<int> never_rests;
    setup.parameters = offline::estimator_parameters_from_noise(
        offline::estimate_sensor_noise(log, setup.nominal.model.torque_constant, &never_rests));
    traces.push_back(
        offline::replay_estimator(setup, offline::estimator_samples(log, setup.nominal.model, 0)));
  }
  return traces;
}

std::string file_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

/// What tpf.train returns, once the weight files are written.
struct TrainResult {
  std::vector<std::string> files;     ///< the weight files written
  std::vector<std::string> contents;  ///< their JSON text
  std::vector<offline::TcnTrainResult> networks;
  std::size_t training_windows = 0, validation_windows = 0;
  offline::HeldOutScore held_out;
  std::vector<std::string> held_out_lines;
};

TrainResult train(const std::vector<std::string>& logs, const NominalModelX& nominal,
                  const std::string& out_path, const offline::CompensatorTrainingOptions& options) {
  std::vector<Log> read;
  for (const std::string& path : logs) {
    read.push_back(offline::read_log(path));
    if (read.back().rows() == 0) throw Error::at(path, 0, "", "no rows: nothing to replay");
  }
  auto [training, held_out] = split_training_logs(std::move(read));
  offline::CompensatorTraining result =
      offline::train_compensator(training_traces(nominal, training), options);
  offline::write_compensator(result, out_path);
  TrainResult out;
  out.held_out = offline::score_held_out(training_traces(
      nominal, held_out, find_compensator_weights(out_path, nominal.model.joint_count())));
  offline::set_held_out_gains(result, out.held_out);
  out.files = offline::write_compensator(result, out_path);
  for (const std::string& f : out.files)
    out.contents.push_back(file_text(f));
  out.networks = std::move(result.results);
  out.training_windows = result.training_windows;
  out.validation_windows = result.validation_windows;
  out.held_out_lines = offline::describe_held_out(
      out.held_out, offline::ReplayParameters{}.compensator_min_held_out_gain);
  return out;
}

py::dict network_dict(const offline::TcnTrainResult& r) {
  py::dict d;
  d["best_epoch"] = r.best_epoch;
  d["epochs"] = r.history.size();
  d["best_validation_loss"] = r.best_validation_loss;
  d["stopped_early"] = r.stopped_early;
  d["stopped_on_time"] = r.stopped_on_time;
  return d;
}

py::dict held_out_dict(const offline::HeldOutScore& s) {
  py::dict d;
  const char* regimes[3] = {"static", "static-to-kinetic", "moving"};
  for (int r = 0; r < 3; ++r) {
    py::dict regime;
    regime["nominal_rmse"] = s.nominal_rmse[r];
    regime["compensated_rmse"] = s.compensated_rmse[r];
    regime["gain"] = s.gain[r];
    regime["rows"] = s.rows[r];
    d[regimes[r]] = regime;
  }
  return d;
}

py::dict train_logs(const py::object& logs, const std::string& params, const std::string& robot,
                    const std::string& out, bool per_joint, int joint_hidden, std::uint64_t seed,
                    int max_epochs, double max_seconds, int epoch_windows, double min_learning_rate,
                    int patience, double split_cutoff, int threads, double break_away_weight,
                    double rest_weight, const std::vector<std::string>& without_input) {
  std::vector<std::string> paths;
  if (py::isinstance<py::str>(logs) || py::hasattr(logs, "__fspath__"))
    paths.push_back(py::str(logs).cast<std::string>());
  else
    paths = logs.cast<std::vector<std::string>>();
  if (paths.empty()) throw py::value_error("no log given");
  if (joint_hidden != offline::kPerJointHiddenSmall &&
      joint_hidden != offline::kPerJointHiddenLarge)
    throw py::value_error("joint_hidden must be 16 or 32");
  if (max_epochs < 1 || threads < 1 || epoch_windows < 0 || patience < 0 || max_seconds < 0 ||
      min_learning_rate < 0 || break_away_weight < 0 || rest_weight < 0)
    throw py::value_error(
        "max_epochs and threads must be at least 1, the other numbers not negative");
  offline::CompensatorTrainingOptions options;
  options.tcn.max_seconds = max_seconds;
  options.tcn.min_learning_rate = min_learning_rate;
  options.tcn.seed = seed;
  options.tcn.max_epochs = max_epochs;
  options.tcn.epoch_windows = epoch_windows;
  options.tcn.patience = patience;
  options.tcn.split_cutoff_hz = split_cutoff;
  options.tcn.threads = threads;
  options.per_joint = per_joint;
  options.joint_hidden = joint_hidden;
  options.static_to_kinetic_weight = break_away_weight;
  options.static_weight = rest_weight;
  for (const std::string& name : without_input)
    options.masked_inputs.push_back(offline::compensator_input_channel(name));
  const NominalModelX nominal = load_nominal_model(params, load_robot_description(robot));
  TrainResult r;
  {
    py::gil_scoped_release unlocked;
    r = train(paths, nominal, out, options);
  }
  py::dict d;
  d["files"] = r.files;
  py::list weights;
  for (const std::string& text : r.contents)
    weights.append(python_of_json(text));
  d["weights"] = weights;
  py::list networks;
  for (const auto& n : r.networks)
    networks.append(network_dict(n));
  d["networks"] = networks;
  d["training_windows"] = r.training_windows;
  d["validation_windows"] = r.validation_windows;
  d["held_out"] = held_out_dict(r.held_out);
  d["held_out_lines"] = r.held_out_lines;
  return d;
}

}  // namespace

void bind_training(py::module_& m) {
  const offline::CompensatorTrainingOptions d;
  m.def("train", &train_logs, py::arg("logs"), py::arg("params"), py::arg("robot"), py::arg("out"),
        py::kw_only(), py::arg("per_joint") = false,
        py::arg("joint_hidden") = offline::kPerJointHiddenSmall, py::arg("seed") = d.tcn.seed,
        py::arg("max_epochs") = d.tcn.max_epochs, py::arg("max_seconds") = 0.0,
        py::arg("epoch_windows") = d.tcn.epoch_windows, py::arg("min_learning_rate") = 5e-5,
        py::arg("patience") = d.tcn.patience, py::arg("split_cutoff") = d.tcn.split_cutoff_hz,
        py::arg("threads") = d.tcn.threads,
        py::arg("break_away_weight") = d.static_to_kinetic_weight,
        py::arg("rest_weight") = d.static_weight,
        py::arg("without_input") = std::vector<std::string>{},
        "`tpf train`: the friction compensator on contact-free `logs` (a path or a list of "
        "paths; the last file held out when the others hold 80 % of the rows, else the last "
        "20 % of the last log) over the parameter file `params` for `robot`; writes the weight "
        "file(s) `out` (per joint: <stem>.joint<j>.json) with their held-out gains. Options as "
        "the CLI's. Returns a dict: files, weights (the files' content), networks (best_epoch, "
        "epochs, best_validation_loss, stopped_early, stopped_on_time), training_windows, "
        "validation_windows, held_out (per regime: nominal_rmse, compensated_rmse [N·m], gain, "
        "rows per joint), held_out_lines.");
}

}  // namespace tpf::python
