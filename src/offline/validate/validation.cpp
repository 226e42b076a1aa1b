#include "offline/validate/validation.hpp"

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "offline/common/not_a_number.hpp"
#include "offline/log/torque_sensor.hpp"
#include "offline/replay/replay_estimator.hpp"
#include "tpf/common/error.hpp"

namespace tpf::offline {
namespace {

/// Identified armature of each joint: the base value of regressor column "Ia<j>" when that
/// column is a base column of its own (0 otherwise).
Eigen::VectorXd identified_armature(const NominalModelX& nominal, std::vector<std::string>& notes) {
  const int N = nominal.model.joint_count();
  Eigen::VectorXd armature = Eigen::VectorXd::Zero(N);
  std::vector<bool> found(static_cast<std::size_t>(N), false);
  for (int i = 0; i < nominal.base_count; ++i) {
    const int c = nominal.base_columns[static_cast<std::size_t>(i)];
    if (c >= 10 * N && c < 11 * N) {
      armature[c - 10 * N] = nominal.base_values[i];
      found[static_cast<std::size_t>(c - 10 * N)] = true;
    }
  }
  for (int j = 0; j < N; ++j)
    if (!found[static_cast<std::size_t>(j)])
      notes.push_back("joint " + std::to_string(j + 1) +
                      ": the armature is grouped with a link inertia in the base parameters; "
                      "the drive loss against the torque sensor leaves I_a·q̈ out");
  return armature;
}

const char* const kRegimeColumns[] = {"static", "static-to-kinetic", "moving", "all"};

double regime_rmse(const RegimeStats& s, int column) {
  return column == 3 ? s.valid.rmse : s.by_regime[static_cast<std::size_t>(column)].rmse;
}

/// " <x>" right-aligned in `width` characters with 3 decimals, or "-" where the regime has no
/// sample (RMSE NaN); `empty` records that a "-" was printed.
std::string rmse_cell(double x, int width, bool& empty) {
  char cell[64];
  if (std::isnan(x)) {
    empty = true;
    std::snprintf(cell, sizeof cell, " %*s", width, "-");
  } else {
    std::snprintf(cell, sizeof cell, " %*.3f", width, x);
  }
  return cell;
}

const char* const kNoSampleNote = "  -: no held-out sample in this regime\n";

}  // namespace

EffortEstimate nominal_estimate(const NominalModelX& nominal, const JointSamples& samples,
                                std::vector<std::string>& notes) {
  const int N = nominal.model.joint_count();
  const Eigen::VectorXd armature = identified_armature(nominal, notes);
  const NominalLinks<double, Eigen::Dynamic> links = nominal_links(nominal);
  Data<double, Eigen::Dynamic> data(nominal.model);
  EffortEstimate e;
  e.name = "nominal model";
  e.effort.setConstant(samples.size(), N, kNaN);
  e.drive_loss.setConstant(samples.size(), N, kNaN);
  Eigen::VectorXd rigid(N), friction(N);
  for (Eigen::Index k = 0; k < samples.size(); ++k) {
    if (!samples.valid[static_cast<std::size_t>(k)]) continue;
    const Eigen::VectorXd q = samples.q.row(k).transpose();
    const Eigen::VectorXd dq = samples.dq.row(k).transpose();
    const Eigen::VectorXd ddq = samples.ddq.row(k).transpose();
    predict_effort(nominal, links, data, q, dq, ddq, rigid, friction);
    e.effort.row(k) = (rigid + friction).transpose();
    e.drive_loss.row(k) = (friction + armature.cwiseProduct(ddq)).transpose();
  }
  return e;
}

EffortEstimate compensated_estimate(const EstimatorSetup<Eigen::Dynamic>& setup, const Log& log,
                                    const EffortEstimate& nominal) {
  const EstimatorTrace trace =
      replay_estimator(setup, estimator_samples(log, setup.nominal.model, 0));
  EffortEstimate e;
  e.name = "with the compensator";
  e.effort = nominal.effort + trace.compensation;
  e.drive_loss = nominal.drive_loss + trace.compensation;
  return e;
}

Validation score_estimates(const Log& log, const JointSamples& samples,
                           const std::vector<EffortEstimate>& estimates) {
  const int joints = samples.joints();
  if (log.rows() != samples.size())
    throw Error(log.source + ": the samples are not this log's (" + std::to_string(samples.size()) +
                " for " + std::to_string(log.rows()) + " rows)");
  Validation v;
  v.effort_unit = samples.units.name();
  v.simulated = samples.simulated;
  for (std::size_t f = 0; f < log.file_count(); ++f)
    v.files.push_back(log.file_path(f));
  for (const EffortEstimate& e : estimates) {
    v.estimate_names.push_back(e.name);
    // In the log's unit: what a person compares with the log (mA for a log of currents).
    const Eigen::MatrixXd residual = samples.units.to_effort(samples.effort - e.effort);
    std::vector<RegimeStats> per_joint;
    for (int j = 0; j < joints; ++j)
      per_joint.push_back(
          regime_stats(residual.col(j), samples.regimes[static_cast<std::size_t>(j)]));
    v.effort.push_back(per_joint);
    std::vector<std::vector<ResidualStats>> per_file;
    for (std::size_t f = 0; f < log.file_count(); ++f) {
      const auto [begin, end] = log.file_rows(f);
      std::vector<ResidualStats> files;
      for (int j = 0; j < joints; ++j) {
        const Eigen::VectorXd r = residual.col(j).segment(begin, end - begin);
        const std::vector<Regime> labels(
            samples.regimes[static_cast<std::size_t>(j)].begin() + begin,
            samples.regimes[static_cast<std::size_t>(j)].begin() + end);
        files.push_back(regime_stats(r, labels).valid);
      }
      per_file.push_back(files);
    }
    v.effort_by_file.push_back(per_file);
  }

  // Against the torque sensor: K_t·i − d − τ_sensor on valid samples of files where it varies.
  const auto sensors = torque_sensor_columns(log, joints);
  v.sensor_notes = torque_sensor_report(log, joints);
  for (int j = 0; j < joints; ++j) {
    const int sensor = log.column(indexed_name("tau_sensor", j + 1));
    const int maker = log.column(indexed_name("tau_maker", j + 1));
    Eigen::VectorXd kt = Eigen::VectorXd::Constant(log.rows(), kNaN), mk = kt;
    std::vector<Eigen::VectorXd> est(estimates.size(), kt);
    for (std::size_t f = 0; f < log.file_count(); ++f) {
      if (!sensor_usable(sensors, f, j)) continue;
      const auto [begin, end] = log.file_rows(f);
      for (Eigen::Index k = begin; k < end; ++k) {
        const double tau_sensor = log.values(k, sensor);
        if (!samples.valid[static_cast<std::size_t>(k)] || std::isnan(tau_sensor)) continue;
        const double drive = samples.effort(k, j);
        kt[k] = drive - tau_sensor;
        if (maker >= 0) mk[k] = log.values(k, maker) - tau_sensor;
        for (std::size_t e = 0; e < estimates.size(); ++e)
          est[e][k] = drive - estimates[e].drive_loss(k, j) - tau_sensor;
      }
    }
    const std::vector<Regime>& labels = samples.regimes[static_cast<std::size_t>(j)];
    SensorScore score;
    score.kt_only = regime_stats(kt, labels);
    score.maker = regime_stats(mk, labels);
    for (const Eigen::VectorXd& r : est)
      score.estimates.push_back(regime_stats(r, labels));
    score.samples = score.kt_only.valid.count;
    for (std::size_t f = 0; f < log.file_count(); ++f) {
      const auto rows = log.file_rows(f);  // not a structured binding: lambdas capture it
      const std::vector<Regime> file_labels(labels.begin() + rows.first,
                                            labels.begin() + rows.second);
      const auto rmse = [&](const Eigen::VectorXd& r) {
        return regime_stats(r.segment(rows.first, rows.second - rows.first), file_labels)
            .valid.rmse;
      };
      std::vector<double> row{rmse(mk), rmse(kt)};
      for (const Eigen::VectorXd& r : est)
        row.push_back(rmse(r));
      score.by_file.push_back(row);
    }
    v.sensor.push_back(score);
  }
  return v;
}

std::string validation_text(const Validation& v) {
  std::string text;
  char line[256];
  bool empty = false;  // a regime without samples was printed as "-"
  const int joints = v.sensor.empty() ? 0 : static_cast<int>(v.sensor.size());
  for (std::size_t e = 0; e < v.estimate_names.size(); ++e) {
    std::snprintf(line, sizeof line,
                  "%sheld-out RMSE of effort - %s [%s]   static  static-to-kinetic   moving      "
                  "all\n",
                  v.simulated ? "SIMULATED " : "", v.estimate_names[e].c_str(),
                  v.effort_unit.c_str());
    text += line;
    for (int j = 0; j < joints; ++j) {
      const RegimeStats& s = v.effort[e][static_cast<std::size_t>(j)];
      std::snprintf(line, sizeof line, "  joint %d", j + 1);
      text.append(line)
          .append(rmse_cell(regime_rmse(s, 0), 35, empty))
          .append(rmse_cell(regime_rmse(s, 1), 18, empty))
          .append(rmse_cell(regime_rmse(s, 2), 8, empty))
          .append(rmse_cell(regime_rmse(s, 3), 8, empty))
          .append("\n");
    }
  }
  if (empty) text += kNoSampleNote;
  empty = false;
  for (const std::string& n : v.sensor_notes)
    text += n + "\n";
  bool any_sensor = false;
  for (const SensorScore& s : v.sensor)
    any_sensor = any_sensor || s.samples > 0;
  if (!any_sensor) return text;
  text += "current-based joint torque against the torque sensor, RMSE [N*m]\n";
  text += "  joint   samples   maker (tau_maker)   Kt only";
  for (const std::string& name : v.estimate_names)
    text += "   Kt - " + name;
  text += "\n";
  for (int j = 0; j < joints; ++j) {
    const SensorScore& s = v.sensor[static_cast<std::size_t>(j)];
    if (s.samples == 0) {
      std::snprintf(line, sizeof line, "  %5d   no usable sensor\n", j + 1);
      text += line;
      continue;
    }
    std::snprintf(line, sizeof line, "  %5d %9zu %19.3f %9.3f", j + 1, s.samples,
                  s.maker.valid.rmse, s.kt_only.valid.rmse);
    text += line;
    for (std::size_t e = 0; e < s.estimates.size(); ++e) {
      std::snprintf(line, sizeof line, " %*.3f", static_cast<int>(v.estimate_names[e].size()) + 7,
                    s.estimates[e].valid.rmse);
      text += line;
    }
    text += "\n";
  }
  text += "the same per regime [N*m]    static  static-to-kinetic   moving\n";
  for (int j = 0; j < joints; ++j) {
    const SensorScore& s = v.sensor[static_cast<std::size_t>(j)];
    if (s.samples == 0) continue;
    const auto row = [&](const std::string& name, const RegimeStats& r) {
      std::snprintf(line, sizeof line, "  joint %d %-18s", j + 1, name.c_str());
      text.append(line)
          .append(rmse_cell(regime_rmse(r, 0), 9, empty))
          .append(rmse_cell(regime_rmse(r, 1), 18, empty))
          .append(rmse_cell(regime_rmse(r, 2), 8, empty))
          .append("\n");
    };
    row("Kt only", s.kt_only);
    for (std::size_t e = 0; e < s.estimates.size(); ++e)
      row("Kt - " + v.estimate_names[e], s.estimates[e]);
  }
  if (empty) text += kNoSampleNote;
  if (v.files.size() < 2) return text;
  text += "the same per file, all regimes [N*m]: Kt only";
  for (const std::string& name : v.estimate_names)
    text.append(" | Kt - ").append(name);
  text += "\n";
  for (std::size_t f = 0; f < v.files.size(); ++f) {
    text.append("  ").append(v.files[f]).append("\n");
    for (int j = 0; j < joints; ++j) {
      const std::vector<double>& r = v.sensor[static_cast<std::size_t>(j)].by_file[f];
      if (std::isnan(r[1])) continue;
      std::snprintf(line, sizeof line, "    joint %d %8.3f", j + 1, r[1]);
      text += line;
      for (std::size_t c = 2; c < r.size(); ++c) {
        std::snprintf(line, sizeof line, " | %8.3f", r[c]);
        text += line;
      }
      text += "\n";
    }
  }
  return text;
}

std::string validation_json(const Validation& v) {
  using nlohmann::json;
  const auto number = [](double x) { return std::isfinite(x) ? json(x) : json(nullptr); };
  json j;
  j["effort_unit"] = v.effort_unit;
  j["files"] = v.files;
  j["simulated"] = v.simulated;
  j["notes"] = v.notes;
  j["sensor_notes"] = v.sensor_notes;
  for (std::size_t e = 0; e < v.estimate_names.size(); ++e) {
    json est;
    est["name"] = v.estimate_names[e];
    for (std::size_t k = 0; k < v.effort[e].size(); ++k) {
      json row;
      for (int c = 0; c < 4; ++c)
        row[kRegimeColumns[c]] = number(regime_rmse(v.effort[e][k], c));
      for (std::size_t f = 0; f < v.effort_by_file[e].size(); ++f)
        row["by_file"].push_back(number(v.effort_by_file[e][f][k].rmse));
      est["effort_rmse"].push_back(row);
    }
    j["estimates"].push_back(est);
  }
  for (const SensorScore& s : v.sensor) {
    const auto by_regime = [&](const RegimeStats& r) {
      json out;
      for (int c = 0; c < 4; ++c)
        out[kRegimeColumns[c]] = number(regime_rmse(r, c));
      return out;
    };
    json row{
        {"samples", s.samples}, {"maker", by_regime(s.maker)}, {"kt_only", by_regime(s.kt_only)}};
    for (std::size_t e = 0; e < s.estimates.size(); ++e)
      row["estimates"].push_back(by_regime(s.estimates[e]));
    for (std::size_t f = 0; f < s.by_file.size(); ++f) {
      json file{{"file", v.files[f]},
                {"maker", number(s.by_file[f][0])},
                {"kt_only", number(s.by_file[f][1])}};
      for (std::size_t c = 2; c < s.by_file[f].size(); ++c)
        file["estimates"].push_back(number(s.by_file[f][c]));
      row["by_file"].push_back(file);
    }
    j["sensor_rmse_newton_metre"].push_back(row);
  }
  return j.dump(2);
}

}  // namespace tpf::offline
