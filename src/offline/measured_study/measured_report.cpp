#include "offline/measured_study/measured_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>

#include "core/common/atomic_file.hpp"
#include "core/common/unoptimised_when_sanitized.hpp"
#include "offline/measured_study/measured_bound_report.hpp"
#include "offline/report/bar_chart.hpp"
#include "offline/report/line_plot.hpp"
#include "offline/report/scatter_plot.hpp"
#include "offline/report/text_format.hpp"

TPF_UNOPTIMISED_WHEN_SANITIZED_BEGIN

namespace tpf::offline {
namespace {

/// Joints (0-based) whose sensor is scored in a split.
std::vector<int> sensor_scored_joints(const MeasuredSplit& split) {
  std::vector<int> joints;
  if (split.columns.empty()) return joints;
  for (std::size_t j = 0; j < split.columns[0].rmse.size(); ++j)
    if (std::isfinite(split.columns[1].rmse[j])) joints.push_back(static_cast<int>(j));
  return joints;
}

/// Names of the estimate columns of a split that meet the target on joint j.
std::vector<std::string> estimates_meeting_target(const MeasuredSplit& split, int j,
                                                  double target) {
  std::vector<std::string> names;
  const double maker = split.columns[0].rmse[static_cast<std::size_t>(j)];
  for (std::size_t c = 2; c < split.columns.size(); ++c)
    if (meets_target(maker, split.columns[c].rmse[static_cast<std::size_t>(j)], target))
      names.push_back(split.columns[c].name);
  return names;
}

std::string rmse_cell(double maker, double rmse) {
  return format_fixed(rmse, 3) + " (" + format_percent_change(maker, rmse) + ")";
}

/// Residual against time and against q̇ for joint j, every trace.
void add_measured_joint_plots(HtmlReport& page, const MeasuredTraces& tr, int j,
                              const std::string& scored_on) {
  std::vector<Series> in_time, in_velocity;
  for (std::size_t n = 0; n < tr.names.size(); ++n) {
    in_time.push_back({tr.names[n], tr.t, tr.residual[n].col(j), ""});
    in_velocity.push_back({tr.names[n], tr.dq.col(j), tr.residual[n].col(j), ""});
  }
  const std::string joint = "joint " + std::to_string(j + 1);
  PlotOptions time_options{joint + ": K_t·i − d − τ_sensor on the held-out files",
                           "time in " + scored_on + " [s]",
                           "residual [N·m]",
                           900,
                           260,
                           true};
  page.figure(line_plot(time_options, in_time));
  PlotOptions velocity_options{
      joint + ": the same against joint velocity", "q̇ [rad/s]", "residual [N·m]", 900, 260, true};
  page.figure(scatter_plot(velocity_options, in_velocity, 800));
}

std::string measured_split_text(const MeasuredSplit& split, double target) {
  std::string text;
  char line[512];
  text += "  joint   Kt only = maker";
  for (std::size_t c = 2; c < split.columns.size(); ++c)
    text += " | " + split.columns[c].name;
  text += "   [N*m, change]\n";
  for (int j : sensor_scored_joints(split)) {
    const double maker = split.columns[0].rmse[static_cast<std::size_t>(j)];
    std::snprintf(line, sizeof line, "  %5d %17.3f", j + 1,
                  split.columns[1].rmse[static_cast<std::size_t>(j)]);
    text += line;
    for (std::size_t c = 2; c < split.columns.size(); ++c) {
      const double r = split.columns[c].rmse[static_cast<std::size_t>(j)];
      std::snprintf(line, sizeof line, " | %7.3f (%+.1f %%)", r, percent_change(maker, r));
      text += line;
    }
    text += estimates_meeting_target(split, j, target).empty() ? "\n" : "  meets the target\n";
  }
  return text;
}

std::string measured_target_sentence(const MeasuredSplit& split, double target) {
  std::vector<std::string> met, missed;
  for (int j : sensor_scored_joints(split)) {
    const std::vector<std::string> names = estimates_meeting_target(split, j, target);
    if (names.empty())
      missed.push_back(std::to_string(j + 1));
    else
      met.push_back(std::to_string(j + 1) + " (" + joined(names, ", ") + ")");
  }
  return "The goal against the arm maker's estimate (the current-based joint torque ≥ " +
         format_sentence("%.0f %%", 100 * target) +
         " closer to the torque sensor than the maker's own K_t·i, on every joint "
         "whose sensor moves) is met on joints " +
         (met.empty() ? std::string("none") : joined(met, "; ")) + " and missed on joints " +
         (missed.empty() ? std::string("none") : joined(missed, ", ")) + ".";
}

/// "joint 1 −9.2 %, joint 3 −45.3 %" for the joints whose error the row changes by ≥ 1 %,
/// lowered (`lowered`) or raised.
std::string changed_joints(const MeasuredColumn& before, const MeasuredColumn& now, bool lowered) {
  std::vector<std::string> joints;
  for (std::size_t j = 0; j < now.rmse.size(); ++j) {
    const double change = percent_change(before.rmse[j], now.rmse[j]);
    if (std::abs(change) >= 1.0 && (change < 0) == lowered)
      joints.push_back("joint " + std::to_string(j + 1) + " " +
                       format_percent_change(before.rmse[j], now.rmse[j]));
  }
  return joined(joints, ", ");
}

/// Σ_j RMSE_j² over the joints where both rows have a value: the summed squared error that a
/// diagnose claim acting on several joints is judged by.
std::pair<double, double> summed_squares(const MeasuredColumn& before, const MeasuredColumn& now) {
  double b = 0, a = 0;
  for (std::size_t j = 0; j < now.rmse.size(); ++j)
    if (std::isfinite(before.rmse[j]) && std::isfinite(now.rmse[j])) {
      b += before.rmse[j] * before.rmse[j];
      a += now.rmse[j] * now.rmse[j];
    }
  return {b, a};
}

}  // namespace

std::string diagnosis_transfer_sentence(const MeasuredResult& r) {
  if (r.diagnosis_effort.size() <= 2)
    return "diagnose wrote no effect: nothing to check on the held-out files.";
  std::vector<std::string> lower, higher;
  for (std::size_t m = 2; m < r.diagnosis_effort.size(); ++m) {
    const MeasuredColumn& before = r.diagnosis_effort[m - 1];
    const MeasuredColumn& now = r.diagnosis_effort[m];
    const std::string down = changed_joints(before, now, true);
    const std::string up = changed_joints(before, now, false);
    const auto [b, a] = summed_squares(before, now);
    if (down.empty() && up.empty()) continue;
    std::string text = now.name.substr(2) + " (";
    if (!down.empty() && !up.empty())
      text += format_percent_change(b, a) +
              " of the squared error summed over the joints: lowers " + down + "; raises " + up;
    else
      text += down.empty() ? up : down;
    (a < b ? lower : higher).push_back(text + ")");
  }
  return "On the held-out files' current, these of diagnose's effects lower the error: " +
         (lower.empty() ? std::string("none") : joined(lower, "; ")) +
         "; these raise it, so they are not claimed here: " +
         (higher.empty() ? std::string("none") : joined(higher, "; ")) +
         ". A claim that passes one held-out file can fail on another: the facts below say why "
         "(few reversals, motions outside the fitting files' range).";
}

/// The oracle compensator's RMSE and its change against the best memoryless model, or "–".
std::string oracle_cell(const MeasuredFloor& f, std::size_t j) {
  const bool trained = j < f.oracle_compensator_rmse.size();
  return trained && std::isfinite(f.oracle_compensator_rmse[j])
             ? rmse_cell(f.best_rmse[j], f.oracle_compensator_rmse[j])
             : "–";
}

Table compensator_floor_table(const MeasuredFloor& f) {
  const double target = f.target;
  Table t;
  const std::string cut = format_number(f.cutoff_hz, 3) + " Hz";
  t.header = {"joint",
              "best memoryless model",
              "its RMSE [N·m]",
              "compensator trained against the sensor [N·m] (change)",
              "oracle: the same trained on the scored files [N·m] (change)",
              "target −" + format_number(100 * target, 3) + " % [N·m]",
              "its residual above " + cut + " (floor) [N·m]",
              "its d above " + cut + " [N·m]",
              "most a model below " + cut + " can gain",
              "target reachable"};
  t.caption =
      "On the held-out files. The floor is the part of the best memoryless model's "
      "residual K_t·i − d − τ_sensor above " +
      cut +
      " (zero-phase 2nd-order Butterworth, per file): the current's noise, which no "
      "model of the motion predicts (the model's own d has little there). A model whose "
      "output stays below " +
      cut +
      " removes at most the rest: RMSE ≥ floor, a gain of at most 1 − floor/RMSE. The oracle "
      "is the compensator trained on the files it is scored on: a bound, not a result.";
  for (std::size_t j = 0; j < f.best_rmse.size(); ++j) {
    if (!std::isfinite(f.best_rmse[j])) continue;
    const double best = f.best_rmse[j], gain = 1.0 - f.floor[j] / best;
    t.rows.push_back(
        {std::to_string(j + 1), f.best_name[j], format_fixed(best, 3),
         std::isfinite(f.compensator_rmse[j]) ? rmse_cell(best, f.compensator_rmse[j]) : "–",
         oracle_cell(f, j), format_fixed((1.0 - target) * best, 3), format_fixed(f.floor[j], 3),
         format_fixed(f.model_high[j], 3), format_sentence("%.1f %%", 100 * gain),
         gain >= target ? "yes" : "no"});
  }
  return t;
}

std::string compensator_floor_sentence(const MeasuredFloor& f) {
  const double target = f.target;
  std::vector<std::string> open, closed;
  for (std::size_t j = 0; j < f.best_rmse.size(); ++j)
    if (std::isfinite(f.best_rmse[j]))
      (1.0 - f.floor[j] / f.best_rmse[j] >= target ? open : closed)
          .push_back(std::to_string(j + 1));
  std::string text =
      "The current's noise leaves room for a compensator " +
      format_sentence("%.0f %%", 100 * target) + " below the best memoryless model on joints " +
      (open.empty() ? std::string("none") : joined(open, ", ")) + " and none on joints " +
      (closed.empty() ? std::string("none") : joined(closed, ", ")) +
      ": there no model of the motion can meet that target on these files.";
  std::vector<std::string> short_even_in_sample, reached_in_sample;
  for (const std::string& joint : open) {
    const std::size_t j = std::stoul(joint) - 1;
    if (j >= f.oracle_compensator_rmse.size() || !std::isfinite(f.oracle_compensator_rmse[j]))
      continue;
    const std::string change = format_percent_change(f.best_rmse[j], f.oracle_compensator_rmse[j]);
    const bool heldout_reaches = std::isfinite(f.compensator_rmse[j]) &&
                                 f.compensator_rmse[j] <= (1.0 - target) * f.best_rmse[j];
    if (f.oracle_compensator_rmse[j] > (1.0 - target) * f.best_rmse[j])
      short_even_in_sample.push_back("joint " + joint + " " + change);
    else if (std::isfinite(f.compensator_rmse[j]) && !heldout_reaches)
      reached_in_sample.push_back("joint " + joint + " " + change + " (held out " +
                                  format_percent_change(f.best_rmse[j], f.compensator_rmse[j]) +
                                  ")");
  }
  if (!short_even_in_sample.empty())
    text +=
        " Where it leaves room, the compensator trained on the scored files themselves, which "
        "sees what it is scored on, still falls short (" +
        joined(short_even_in_sample, ", ") +
        " against the best memoryless model): over its inputs and on files this short the "
        "network cannot learn that error, so these files do not support the target there "
        "either.";
  if (!reached_in_sample.empty())
    text += " The compensator trained on the scored files reaches the target on " +
            joined(reached_in_sample, ", ") +
            ": the error is learnable there, but what the network learns on the fitting files "
            "does not carry over to the held-out ones.";
  return text;
}

std::string columns_sentence(const MeasuredResult& r) {
  std::string taus;
  for (Eigen::Index j = 0; j < r.low_pass_time_constants.size(); ++j)
    taus += (j ? " / " : " ") + format_number(1000 * r.low_pass_time_constants[j], 3);
  return "'friction against the sensor': identify --friction-from-sensor, each joint's friction "
         "fitted against its torque sensor (K_t·i − (τ_sensor + I_a·q̈)) instead of against "
         "the effort less the rigid body identified on the same few seconds of motion. '+ "
         "current low-pass': the "
         "same with the motor current through a causal first-order low-pass, time constant "
         "chosen per joint on the fitting files (joints 1–7, ms:" +
         taus +
         "; 0 = none): the published sensor is far smoother than the current, so filtering "
         "the current brings it closer, at the cost of that much lag, which a contact "
         "detector pays. The run-time estimator does not filter the current. '" +
         std::string(kWithoutInertiaPriorColumn) +
         "': identify --no-inertia-prior, the plain least-squares fit. The fitting files do not "
         "excite every inertia: that fit's mass matrix M(q) is not positive definite, so every "
         "other column's rigid body is pulled toward the robot file's inertias (identify's "
         "default), as far as M(q) needs.";
}

bool meets_target(double maker, double rmse, double target) {
  return std::isfinite(maker) && std::isfinite(rmse) && rmse <= (1.0 - target) * maker;
}

Table measured_table(const MeasuredSplit& split, double target) {
  Table t;
  t.header = {"joint", "samples", "maker = Kt only [N·m]"};
  for (std::size_t c = 2; c < split.columns.size(); ++c)
    t.header.push_back(split.columns[c].name + " [N·m] (change)");
  t.header.push_back("meets −" + format_number(100 * target, 3) + " %");
  t.caption = "RMSE of the current-based joint torque against the torque sensor on " +
              split.scored_on + " (fitted on " + split.fitted_on +
              "); every regime, samples where the sensor varies.";
  for (std::size_t j = 0; j < split.columns[0].rmse.size(); ++j) {
    std::vector<std::string> row{std::to_string(j + 1)};
    const SensorScore& s = split.validation.sensor[j];
    if (s.samples == 0) {
      row.push_back("0");
      row.push_back("no usable sensor");
      t.rows.push_back(row);
      continue;
    }
    const double maker = split.columns[0].rmse[j];
    row.push_back(std::to_string(s.samples));
    row.push_back(format_fixed(split.columns[1].rmse[j], 3));
    std::size_t meeting = 0;
    for (std::size_t c = 2; c < split.columns.size(); ++c) {
      const bool meets = meets_target(maker, split.columns[c].rmse[j], target);
      meeting += meets;
      row.push_back(rmse_cell(maker, split.columns[c].rmse[j]) + (meets ? " \u2713" : ""));
    }
    row.push_back(meeting == 0 ? "no"
                               : "yes (\u2713): " + std::to_string(meeting) + " of " +
                                     std::to_string(split.columns.size() - 2));
    t.rows.push_back(row);
  }
  return t;
}

Table diagnosis_effort_table(const MeasuredResult& r) {
  Table t;
  t.header = {"model"};
  const std::size_t joints =
      r.diagnosis_effort.empty() ? 0 : r.diagnosis_effort.front().rmse.size();
  for (std::size_t j = 0; j < joints; ++j)
    t.header.push_back("joint " + std::to_string(j + 1));
  t.caption =
      "diagnose's effects against the held-out files' current: RMSE of the effort less "
      "the model's whole prediction (rigid body included) on " +
      r.forward.scored_on + " [mA], change against the row above.";
  for (std::size_t m = 0; m < r.diagnosis_effort.size(); ++m) {
    std::vector<std::string> row{r.diagnosis_effort[m].name};
    for (std::size_t j = 0; j < joints; ++j) {
      const double now = r.diagnosis_effort[m].rmse[j];
      row.push_back(m < 2
                        ? format_number(now, 4)
                        : format_number(now, 4) + " (" +
                              format_percent_change(r.diagnosis_effort[m - 1].rmse[j], now) + ")");
    }
    t.rows.push_back(row);
  }
  return t;
}

Table candidate_table(const MeasuredResult& r) {
  Table t;
  t.header = {"candidate"};
  int joints = 0;
  for (const SensorCandidate& c : r.candidates)
    joints = std::max(joints, c.joint + 1);
  for (int j = 0; j < joints; ++j)
    t.header.push_back("joint " + std::to_string(j + 1));
  t.caption =
      "Change of the held-out RMSE of K_t·i − d − τ_sensor per joint (d: the identified model's "
      "drive loss). Each candidate is fitted on the fitting files on top of Coulomb + viscous "
      "refitted against the sensor (the base, first row, itself judged against the model "
      "alone); ✔ = claimed: the held-out RMSE falls by ≥ 5 % and the in-file one falls too. "
      "Fitted values in measured.json.";
  std::vector<std::string> keys;
  for (const SensorCandidate& c : r.candidates)
    if (std::find(keys.begin(), keys.end(), c.key) == keys.end()) keys.push_back(c.key);
  for (const std::string& key : keys) {
    std::vector<std::string> row(static_cast<std::size_t>(joints) + 1, "–");
    for (const SensorCandidate& c : r.candidates) {
      if (c.key != key) continue;
      row[0] = c.title;
      row[static_cast<std::size_t>(c.joint) + 1] =
          format_percent_change(c.heldout_before, c.heldout_after) + (c.supported ? " ✔" : "");
    }
    t.rows.push_back(row);
  }
  return t;
}

std::string candidate_summary(const MeasuredResult& r) {
  std::vector<std::string> keys, claimed, none;
  for (const SensorCandidate& c : r.candidates)
    if (std::find(keys.begin(), keys.end(), c.key) == keys.end()) keys.push_back(c.key);
  for (const std::string& key : keys) {
    std::string title, joints, ambiguous;
    for (const SensorCandidate& c : r.candidates) {
      if (c.key != key) continue;
      title = c.title;
      if (!c.supported) continue;
      joints += (joints.empty() ? "" : ", ") + std::to_string(c.joint + 1);
      if (!c.ambiguous_with.empty())
        ambiguous +=
            "; joint " + std::to_string(c.joint + 1) + " ambiguous with the " + c.ambiguous_with;
    }
    (joints.empty() ? none : claimed)
        .push_back(joints.empty() ? title : title + " (joints " + joints + ambiguous + ")");
  }
  return "Claimed, held out by file: " +
         (claimed.empty() ? std::string("none") : joined(claimed, "; ")) +
         ". Not supported on any joint: " +
         (none.empty() ? std::string("none") : joined(none, "; ")) + ".";
}

std::string measured_headline(const MeasuredResult& r, double target) {
  std::string text = std::string(kMeasuredLabel) + "\n";
  text += "current-based joint torque against the torque sensor, RMSE on the held-out files " +
          r.forward.scored_on + " (fitted on " + r.forward.fitted_on + "):\n";
  text += measured_split_text(r.forward, target);
  if (!r.reverse.columns.empty()) {
    text += "reverse split, fitted on " + r.reverse.fitted_on + ", scored on " +
            r.reverse.scored_on + ":\n";
    text += measured_split_text(r.reverse, target);
  }
  text += measured_target_sentence(r.forward, target) + "\n";
  for (const std::string& verdict : measured_bound_verdicts(r.bound, r.reverse_bound))
    text += "  " + verdict + "\n";
  text += columns_sentence(r) + "\n";
  if (!r.floor.best_rmse.empty()) text += compensator_floor_sentence(r.floor) + "\n";
  if (!r.diagnosis_heldout.empty()) text += diagnosis_transfer_sentence(r) + "\n";
  std::vector<std::string> claimed;
  for (const SensorCandidate& c : r.candidates)
    if (c.supported)
      claimed.push_back(
          c.key + " j" + std::to_string(c.joint + 1) + " " +
          format_percent_change(c.heldout_before, c.heldout_after) +
          (c.ambiguous_with.empty() ? "" : " (ambiguous with " + c.ambiguous_with + ")"));
  text += "candidate effects that lower the held-out error: " +
          (claimed.empty() ? std::string("none") : joined(claimed, ", ")) + "\n";
  return text;
}

namespace {

/// 3 of "a.csv.gz + b.csv.gz + c.csv.gz".
std::size_t file_count(const std::string& files) {
  std::size_t n = 1;
  for (std::size_t at = files.find(" + "); at != std::string::npos; at = files.find(" + ", at + 3))
    ++n;
  return n;
}

}  // namespace

namespace {

/// The columns the first screen and the short summary show: maker, then tpf's identified model
/// and its friction fitted against the sensor with the current low-pass (when present), each
/// with its short name.
std::vector<std::pair<int, std::string>> headline_columns(const MeasuredSplit& split) {
  std::vector<std::pair<int, std::string>> columns{{0, "maker's estimate K_t·i"}};
  const std::vector<std::pair<std::string, std::string>> shown{
      {"after identification", "tpf, identified"},
      {"+ current low-pass", "tpf, friction against the sensor + current low-pass"}};
  for (const auto& [name, label] : shown)
    if (const int c = measured_column(split, name); c >= 0) columns.emplace_back(c, label);
  return columns;
}

}  // namespace

std::string measured_brief(const MeasuredResult& r, double target) {
  const MeasuredSplit& split = r.forward;
  const auto columns = headline_columns(split);
  std::string text = std::string(kMeasuredLabel) + "\n";
  text +=
      "RMSE against the torque sensor on the held-out files [N·m], change against the "
      "maker's estimate:\n  joint";
  for (const auto& [c, label] : columns)
    text += " | " + label;
  text += " | goal −" + format_sentence("%.0f %%", 100 * target) + "\n";
  for (int j : sensor_scored_joints(split)) {
    const auto jj = static_cast<std::size_t>(j);
    const double maker = split.columns[0].rmse[jj];
    char line[64];
    std::snprintf(line, sizeof line, "  %5d | %6.3f", j + 1, maker);
    text += line;
    for (std::size_t k = 1; k < columns.size(); ++k) {
      const double rmse = split.columns[static_cast<std::size_t>(columns[k].first)].rmse[jj];
      std::snprintf(line, sizeof line, " | %6.3f (%+.1f %%)", rmse, percent_change(maker, rmse));
      text += line;
    }
    text += estimates_meeting_target(split, j, target).empty() ? " | missed\n" : " | met\n";
  }
  return text;
}

void add_measured_headline(HtmlReport& page, const MeasuredResult& r, double target, int width) {
  const MeasuredSplit& split = r.forward;
  std::vector<std::string> groups;
  std::vector<BarSeries> series;
  std::vector<int> columns;
  for (const auto& [c, label] : headline_columns(split)) {
    columns.push_back(c);
    series.push_back({label, {}, c == 0 ? "#7a8594" : ""});
  }
  std::vector<std::string> met, missed;
  for (int j : sensor_scored_joints(split)) {
    const auto jj = static_cast<std::size_t>(j);
    groups.push_back("joint " + std::to_string(j + 1));
    for (std::size_t k = 0; k < columns.size(); ++k)
      series[k].values.push_back(split.columns[static_cast<std::size_t>(columns[k])].rmse[jj]);
    (estimates_meeting_target(split, j, target).empty() ? missed : met)
        .push_back(std::to_string(j + 1));
  }
  page.heading("Kinova Gen3 (MEASURED): error against the torque sensor");
  page.figure(bar_chart({"", "", "RMSE on held-out files [N·m]", width, 260, true}, groups, series),
              "Held out by file: fitted on " + std::to_string(file_count(split.fitted_on)) +
                  " files, scored on " + std::to_string(file_count(split.scored_on)) +
                  " others. tpf's goal, " + format_sentence("%.0f %%", 100 * target) +
                  " below the maker's estimate: met on joints " +
                  (met.empty() ? std::string("none") : joined(met, ", ")) + "; missed on " +
                  (missed.empty() ? std::string("none") : joined(missed, ", ")) +
                  ". Data: Kinova Gen3 logs, W. Chiha, MIT licence.");
}

void add_measured_summary(HtmlReport& page, const MeasuredResult& r, double target) {
  page.subtitle(kMeasuredLabel);
  page.paragraph("Held out by file: fitted on " + r.forward.fitted_on + ", scored on " +
                 r.forward.scored_on + " against the joint torque sensor, in " +
                 format_number(r.seconds, 3) +
                 " s. Details, the reverse split, the candidate "
                 "effects, what the files cannot decide and the plots: measured.html.");
  page.links({{"measured.html", "measured",
               "— the Kinova Gen3 logs: before/after per joint, candidate effects, plots"}});
  page.table(measured_table(r.forward, target));
  page.paragraph(measured_target_sentence(r.forward, target));
}

namespace {

/// The reverse split's table, target and low-pass time constants.
void add_reverse_section(HtmlReport& page, const MeasuredResult& r, const MeasuredOptions& o) {
  page.open_details("The reverse split: fitted on the scored files, scored on the fitting ones");
  page.table(measured_table(r.reverse, o.target_reduction));
  page.paragraph(measured_target_sentence(r.reverse, o.target_reduction));
  std::string taus;
  for (Eigen::Index j = 0; j < r.reverse_low_pass_time_constants.size(); ++j)
    taus += (j ? " / " : " ") + format_number(1000 * r.reverse_low_pass_time_constants[j], 3);
  page.paragraph("Low-pass time constants chosen on this split's fitting files (joints 1–7, ms):" +
                 taus + ".");
  page.close_details();
}

/// What the two compensators are and how they trained.
void add_compensator_section(HtmlReport& page, const MeasuredResult& r, const MeasuredOptions& o) {
  const auto epochs = [](const CompensatorTraining& t) {
    std::string text;
    for (const TcnTrainResult& n : t.results)
      text.append(" ").append(std::to_string(n.best_epoch));
    return text;
  };
  std::string masked;
  for (int c : o.compensator_masked_inputs)
    masked += std::string(masked.empty() ? " " : ", ") +
              kCompensatorInputNames[static_cast<std::size_t>(c)];
  if (masked.empty()) masked = " none";
  const long parameters =
      r.training.results.empty()
          ? 0
          : static_cast<long>(tcn_parameter_count(r.training.results.front().best.architecture));
  const std::size_t windows =
      r.training.results.empty() ? 0 : r.training.training_windows / r.training.results.size();
  page.paragraph(
      "Compensator: one " + std::to_string(o.joint_hidden) +
      "-channel network per joint, trained by tpf train's machinery on the fitting files (" +
      std::to_string(o.training_epochs) +
      " epochs at most), scored through validate's "
      "compensator path (the run-time estimator replayed on the held-out files, its output "
      "counted as drive loss). 'with the compensator' sits on the identified model and learns "
      "the run-time estimator's current residual τ_res = K_t·i − (rigid body + friction), as "
      "tpf train does on contact-free logs (best epochs" +
      epochs(r.training) + ", " + format_number(r.training.seconds, 3) +
      " s); on these files that residual holds the rigid body's error too, which a per-joint "
      "network that sees only its own joint cannot predict. The last column sits on the "
      "friction fitted against the sensor and learns K_t·i − d − τ_sensor wherever the sensor "
      "varies (best epochs" +
      epochs(r.sensor_training) + "). Inputs the networks do not see:" + masked +
      " (held at 0 in training and removed from the networks): the held-out files move where "
      "the fitting files never went (below), and against the sensor τ̂_fric,s holds the rigid "
      "body's error, not friction. " +
      std::to_string(parameters) + " coefficients per network against " + std::to_string(windows) +
      " training windows of " + std::to_string(TcnTrainOptions{}.window_outputs) +
      " strongly correlated samples each; a best epoch of 1 or 2 means that training made the "
      "fitting files' own held-out block worse from the start.");
}

/// diagnose's findings on the fitting files and its effects against the held-out current.
void add_diagnosis_section(HtmlReport& page, const MeasuredResult& r) {
  page.open_details("What diagnose adds");
  page.paragraph(
      "diagnose ran on the fitting files and held out the last one, " + r.diagnosis_heldout +
      ", with the files that repeat its motion: it claims an effect only if it lowers the "
      "current residual there, on each other group of files held out one at a time and, for a term "
      "that extrapolates in q, on the held-out samples outside the range of q its fit saw. The "
      "column "
      "\"diagnose's model\" above scores its written model against the sensor on the held-out "
      "files; the table below adds its written effects one at a time against the held-out "
      "files' current. Its findings on the fitting files:");
  page.list(r.diagnosis_findings);
  if (!r.diagnosis_unseen.empty()) page.paragraph(r.diagnosis_unseen);
  page.table(diagnosis_effort_table(r));
  page.paragraph(diagnosis_transfer_sentence(r));
  page.close_details();
}

}  // namespace

void write_measured_report(const MeasuredResult& r, const MeasuredOptions& o,
                           const std::filesystem::path& folder) {
  HtmlReport page("tpf: the loop on measured data (Kinova Gen3)");
  page.mark_measured("Kinova Gen3 logs, W. Chiha, MIT licence (data/real/kinova-gen3/SOURCE.md)");
  page.subtitle(kMeasuredLabel);
  add_measured_headline(page, r, o.target_reduction, 900);
  page.paragraph(
      "K_t·i (the maker's own current-based joint torque: TorqueCur = K_t·Cur exactly) against "
      "the torque sensor behind each gear, before and after the model: K_t·i − d with d the "
      "drive loss the model predicts (friction + armature·q̈). Held out by file: nothing scored "
      "was fitted on. " +
      format_number(r.seconds, 3) + " s.");
  page.open_details("Every model against the sensor, per joint (held out by file)");
  page.table(measured_table(r.forward, o.target_reduction));
  page.paragraph(measured_target_sentence(r.forward, o.target_reduction));
  page.paragraph(columns_sentence(r));
  page.close_details();
  if (!r.reverse.columns.empty()) add_reverse_section(page, r, o);
  if (!r.training.results.empty()) {
    page.open_details("The compensators: what they learn and how they trained");
    add_compensator_section(page, r, o);
    page.close_details();
  }
  if (!r.floor.best_rmse.empty()) {
    page.open_details("The compensator against the best memoryless model, and the noise floor");
    page.table(compensator_floor_table(r.floor));
    page.paragraph(compensator_floor_sentence(r.floor));
    page.close_details();
  }
  if (!r.bound.maker.empty()) add_measured_bound_section(page, r.bound, r.reverse_bound);
  if (!r.diagnosis_heldout.empty()) add_diagnosis_section(page, r);
  page.open_details("What the residual holds: candidates against the sensor");
  page.table(candidate_table(r));
  page.paragraph(candidate_summary(r));
  page.close_details();
  page.open_details("What these files cannot decide");
  page.list(measured_fact_lines(r.facts));
  if (!r.notes.empty()) page.list(r.notes);
  page.close_details();
  page.open_details("Residuals on the held-out files, per joint");
  for (int j : sensor_scored_joints(r.forward))
    add_measured_joint_plots(page, r.traces, j, r.forward.scored_on);
  page.close_details();
  page.write(folder / "measured.html");
  AtomicFile json(folder / "measured.json");
  json.write(measured_json(r, o.target_reduction));
  json.commit();
}

std::string measured_json(const MeasuredResult& r, double target) {
  using nlohmann::json;
  const auto number = [](double x) { return std::isfinite(x) ? json(x) : json(nullptr); };
  const auto split = [&](const MeasuredSplit& s) {
    json out{{"fitted_on", s.fitted_on}, {"scored_on", s.scored_on}};
    for (const MeasuredColumn& c : s.columns) {
      json col{{"name", c.name}};
      for (double x : c.rmse)
        col["rmse_newton_metre"].push_back(number(x));
      out["columns"].push_back(col);
    }
    out["validation"] = json::parse(validation_json(s.validation));
    return out;
  };
  json j{{"measured", true},
         {"label", kMeasuredLabel},
         {"target_reduction", target},
         {"seconds", r.seconds}};
  j["forward"] = split(r.forward);
  json met = json::array();
  for (int joint : sensor_scored_joints(r.forward))
    if (!estimates_meeting_target(r.forward, joint, target).empty()) met.push_back(joint + 1);
  j["forward"]["joints_meeting_target"] = met;
  if (!r.reverse.columns.empty()) {
    j["reverse"] = split(r.reverse);
    json rmet = json::array();
    for (int joint : sensor_scored_joints(r.reverse))
      if (!estimates_meeting_target(r.reverse, joint, target).empty()) rmet.push_back(joint + 1);
    j["reverse"]["joints_meeting_target"] = rmet;
  }
  for (const SensorCandidate& c : r.candidates)
    j["candidates"].push_back({{"key", c.key},
                               {"title", c.title},
                               {"joint", c.joint + 1},
                               {"detail", c.detail},
                               {"value", number(c.value)},
                               {"ambiguous_with", c.ambiguous_with},
                               {"fit_before", number(c.fit_before)},
                               {"fit_after", number(c.fit_after)},
                               {"heldout_before", number(c.heldout_before)},
                               {"heldout_after", number(c.heldout_after)},
                               {"claimed", c.supported}});
  json effort = json::array();
  for (const MeasuredColumn& c : r.diagnosis_effort) {
    json row{{"name", c.name}};
    for (double x : c.rmse)
      row["rmse_effort"].push_back(number(x));
    effort.push_back(row);
  }
  j["diagnosis"] = {{"heldout_file", r.diagnosis_heldout},
                    {"effort_on_scoring_files", effort},
                    {"findings", r.diagnosis_findings},
                    {"not_seen_by_the_sensor", r.diagnosis_unseen}};
  if (!r.floor.best_rmse.empty()) {
    json floor{{"cutoff_hz", r.floor.cutoff_hz}, {"target_below_best", r.floor.target}};
    for (std::size_t k = 0; k < r.floor.best_rmse.size(); ++k) {
      const double most = 1.0 - r.floor.floor[k] / r.floor.best_rmse[k];
      floor["joints"].push_back(
          {{"joint", k + 1},
           {"best_memoryless", r.floor.best_name[k]},
           {"best_rmse", number(r.floor.best_rmse[k])},
           {"compensator_rmse", number(r.floor.compensator_rmse[k])},
           {"oracle_compensator_rmse", number(k < r.floor.oracle_compensator_rmse.size()
                                                  ? r.floor.oracle_compensator_rmse[k]
                                                  : std::numeric_limits<double>::quiet_NaN())},
           {"floor_rmse", number(r.floor.floor[k])},
           {"model_above_cutoff_rmse", number(r.floor.model_high[k])},
           {"most_reduction", number(most)},
           {"target_reachable", most >= r.floor.target}});
    }
    j["compensator_floor"] = floor;
  }
  if (!r.bound.maker.empty()) {
    j["bound"] = json::parse(measured_bound_json(r.bound));
    j["reverse_bound"] = json::parse(measured_bound_json(r.reverse_bound));
  }
  j["facts"] = measured_fact_lines(r.facts);
  return j.dump(2);
}

}  // namespace tpf::offline

TPF_UNOPTIMISED_WHEN_SANITIZED_END
