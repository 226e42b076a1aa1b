#include "offline/evaluate/evaluation.hpp"

#include <cmath>
#include <nlohmann/json.hpp>

#include "offline/calibrate/estimator_calibration.hpp"
#include "core/common/unoptimised_when_sanitized.hpp"
#include "offline/replay/estimator_samples.hpp"
#include "tpf/common/error.hpp"

namespace tpf::offline {
namespace {

using Vec = Eigen::VectorXd;

/// τ̂_ext [N·m] of each modality per row (T × N): tactile J_vᵀ(−F_n·n), the proprioceptive
/// estimate, and the estimator's fused answer (EstimatorOutput::external).
std::array<Eigen::MatrixXd, kModalityCount> external_torques(const EstimatorTrace& tr) {
  // τ_ext = −residual (ExternalTorque).
  return {tr.torque_tactile, -tr.proprioceptive, -tr.external};
}

/// Per row: does the modality say "contact"? Tactile: a pad; proprioceptive: any joint outside
/// its band; fusion: the estimator's EstimatorOutput::contact — a pad, or the combined estimate
/// outside its band for parameters.torque_alarm_samples cycles in a row.
std::array<Eigen::VectorXi, kModalityCount> detections(const EstimatorTrace& tr) {
  return {tr.contact.cwiseMax(0), any_joint_outside_band(tr.proprioceptive),
          tr.estimator_contact.cwiseMax(0)};
}

Eigen::MatrixXd columns(const Log& log, const std::string& prefix, int count) {
  Eigen::MatrixXd m(log.rows(), count);
  for (int j = 0; j < count; ++j)
    m.col(j) = log.col(indexed_name(prefix, j + 1));
  return m;
}

Eigen::MatrixXd ground_truth_force(const Log& log) {
  Eigen::MatrixXd f(log.rows(), 3);
  f << log.col("gt_fx"), log.col("gt_fy"), log.col("gt_fz");
  return f;
}

void contact_metrics(const Log& log, const EstimatorTrace& tr, Evaluation& ev) {
  const Eigen::MatrixXd force = ground_truth_force(log);
  const Eigen::VectorXd gt_contact = log.col("gt_contact");
  const auto events = contact_events(gt_contact, force);
  const auto detected = detections(tr);
  for (int m = 0; m < kModalityCount; ++m)
    ev.detection[m] = detection_stats(tr.t, events, force, detected[m]);
  // Force error: static rows with one contact on the pad the skin reports, where the arm observes
  // the shear (the fused wrench is valid) and the push is at least 1 N.
  std::vector<Eigen::Index> rows;
  for (Eigen::Index k = 0; k < tr.rows(); ++k) {
    if (!(gt_contact[k] > 0) || tr.pad[k] != static_cast<int>(gt_contact[k]) - 1) continue;
    if (tr.wrench_valid[k] != 1 || tr.state[k] == static_cast<int>(ContactState::Dynamic)) continue;
    if (force.row(k).norm() >= 1.0) rows.push_back(k);
  }
  const std::array<const Eigen::MatrixXd*, kModalityCount> estimate{
      &tr.force_tactile, &tr.force_proprioceptive, &tr.force_world};
  for (int m = 0; m < kModalityCount; ++m)
    ev.force[m] = force_error(*estimate[m], force, rows);
}

void teaching_metrics(const Log& log, const EstimatorTrace& tr, Evaluation& ev) {
  const int joints = ev.joints;
  const Eigen::MatrixXd truth = columns(log, "gt_tau_ext", joints);
  const Eigen::VectorXd gt_contact = log.col("gt_contact");
  const auto torque = external_torques(tr);
  ev.teaching_torque = torque;
  ev.teaching_truth = truth;
  TeachingErrors& te = ev.teaching;
  std::array<Vec, kModalityCount> sum{}, sum_onset{};
  for (auto* a : {&sum, &sum_onset})
    for (auto& v : *a)
      v.setZero(joints);
  Vec onset_count = Vec::Zero(joints);
  Vec last_start = Vec::Constant(joints, -1e9);
  for (Eigen::Index k = 1; k < tr.rows(); ++k) {
    for (int j = 0; j < joints; ++j)
      if (std::abs(tr.dq(k - 1, j)) < 1e-4 && std::abs(tr.dq(k, j)) >= 1e-4)
        last_start[j] = tr.t[k];
    if (!(gt_contact[k] > 0) || !std::isfinite(tr.t[k])) continue;
    ++te.contact_rows;
    for (int m = 0; m < kModalityCount; ++m) {
      for (int j = 0; j < joints; ++j) {
        const double e = torque[m](k, j) - truth(k, j);
        if (!std::isfinite(e)) continue;
        sum[m][j] += e * e;
        if (tr.t[k] - last_start[j] < 0.3) {
          sum_onset[m][j] += e * e;
          if (m == 0) onset_count[j] += 1;
        }
      }
    }
  }
  te.onset_rows = static_cast<std::size_t>(onset_count.sum());
  for (int m = 0; m < kModalityCount; ++m) {
    te.rmse[m] = (sum[m] / double(std::max<std::size_t>(te.contact_rows, 1))).cwiseSqrt();
    te.onset_rmse[m] = (sum_onset[m].array() / onset_count.array().max(1.0)).sqrt().matrix();
  }
}

}  // namespace

const char* modality_name(Modality m) {
  switch (m) {
    case Modality::Tactile:
      return "tactile-only";
    case Modality::Proprioceptive:
      return "proprioceptive-only";
    case Modality::Fusion:
      return "fusion";
  }
  return "?";
}

namespace {

/// What calibration set, per joint, for the report: σ's and bands in the effort unit of `u`.
Calibration calibration_of(const ReplayParameters& p, const DriveUnits& u) {
  const auto in_unit = [&](const ReplayVector& tau) {
    Vec e(tau.size());
    for (int j = 0; j < tau.size(); ++j)
      e[j] = u.to_effort(j, tau[j]);
    return e;
  };
  Calibration c;
  c.sigma_nominal = in_unit(p.nominal_sigma);
  c.sigma_fused = in_unit(p.fused_sigma);
  c.proprioceptive_band = in_unit(p.dead_band_factor * p.nominal_sigma);
  c.fusion_moving_band = in_unit(p.dead_band_factor * p.fused_sigma);
  c.fusion_static_band = in_unit(p.static_dead_band);
  c.compensator_speed_limit = p.compensator_speed_limit;
  c.compensator_acceleration_limit = p.compensator_acceleration_limit;
  c.torque_alarm_samples = p.torque_alarm_samples;
  c.tactile_n = p.skin.force_gain * p.skin.detector.on_level_kpa * 1000.0 * 0.0025;
  return c;
}

}  // namespace

Evaluation evaluate(ReplaySetup& setup, const EvaluationLogs& logs,
                    const std::function<void(const std::string&)>& progress) {
  const auto say = [&](const std::string& line) {
    if (progress) progress(line);
  };
  if (!logs.calibration || logs.excitation.empty())
    throw Error::at("evaluate", 0, "logs", "a calibration log and an excitation log are needed");
  Evaluation ev;
  ev.joints = setup.nominal.model.joint_count();
  ev.has_skin = !setup.pads.empty();
  ev.units = drive_units(setup.nominal.model,
                         effort_unit_of_column(logs.excitation.front()->effort_prefix()));
  const int pads = static_cast<int>(setup.pads.size());

  say("evaluate: calibrating the dead bands on " + logs.calibration->source);
  calibrate_with_compensator(setup, *logs.calibration);
  ev.calibration = calibration_of(setup.parameters, ev.units);

  std::vector<ResidualRecording> recordings;
  for (const Log* log : logs.excitation) {
    say("evaluate: estimator over " + log->source);
    EstimatorTrace tr = replay_estimator(setup, estimator_samples(*log, setup.nominal.model, pads));
    // Table I in the logs' unit (mA for logs of currents), as the original reports it.
    recordings.push_back({tr.t, tr.dq, ev.units.to_effort(tr.residual),
                          ev.units.to_effort(tr.residual - tr.compensation)});
    ev.excitation_rows += tr.rows();
    if (recordings.size() == 1) ev.excitation_trace = std::move(tr);
  }
  // The residuals "meet" when they differ by less than the effort noise (the static band / 3).
  ev.table = residual_table(recordings, ev.calibration.fusion_static_band / 3.0);
  ev.rest_memory = rest_memory(ev.table, rest_noise_floor(recordings));

  if (logs.contacts) {
    if (!ev.has_skin)
      throw Error::at(logs.contacts->source, 0, "pads",
                      "a static-contacts log scores the skin, and this arm has no pad layout");
    say("evaluate: estimator over " + logs.contacts->source);
    ev.contacts_trace =
        replay_estimator(setup, estimator_samples(*logs.contacts, setup.nominal.model, pads));
    contact_metrics(*logs.contacts, ev.contacts_trace, ev);
    ev.has_contacts = true;
  }
  if (logs.teaching) {
    say("evaluate: estimator over " + logs.teaching->source);
    ev.teaching_trace =
        replay_estimator(setup, estimator_samples(*logs.teaching, setup.nominal.model, pads));
    teaching_metrics(*logs.teaching, ev.teaching_trace, ev);
    ev.has_teaching = true;
  }
  if (logs.teaching_scenario) {
    say("evaluate: closed-loop teaching, the admittance controller following each estimator");
    ev.closed_loop = closed_loop_teaching(setup, *logs.teaching_scenario, logs.teaching_seed,
                                          logs.teaching_duration_s);
    ev.has_closed_loop = true;
  }
  return ev;
}

TPF_UNOPTIMISED_WHEN_SANITIZED_BEGIN
std::string evaluation_json(const Evaluation& ev) {
  using nlohmann::json;
  const auto vec = [](const auto& v) {
    json a = json::array();
    for (Eigen::Index i = 0; i < v.size(); ++i)
      a.push_back(std::isfinite(double(v[i])) ? json(double(v[i])) : json(nullptr));
    return a;
  };
  const auto num = [](double x) { return std::isfinite(x) ? json(x) : json(nullptr); };
  const auto stats = [&](const ResidualStats& s) {
    return json{
        {"count", s.count}, {"rmse", num(s.rmse)}, {"std", num(s.std)}, {"mean", num(s.mean)}};
  };
  json j;
  const Calibration& c = ev.calibration;
  j["simulated"] = true;
  j["sigma"] = {{"nominal", vec(c.sigma_nominal)}, {"fused", vec(c.sigma_fused)}};
  j["torque_alarm_samples"] = c.torque_alarm_samples;
  j["compensator_speed_limit"] = vec(c.compensator_speed_limit);
  j["compensator_acceleration_limit"] = vec(c.compensator_acceleration_limit);
  j["dead_bands"] = {{"proprioceptive", vec(c.proprioceptive_band)},
                     {"fusion_moving", vec(c.fusion_moving_band)},
                     {"fusion_static", vec(c.fusion_static_band)},
                     {"tactile_n", ev.has_skin ? num(c.tactile_n) : json("no skin")}};
  json rows = json::array();
  for (const ResidualRow& r : ev.table)
    rows.push_back(
        {{"joint", r.joint < 0 ? json("all") : json(r.joint + 1)},
         {"regime", std::string(regime_name(r.regime))},
         {"nominal", stats(r.nominal)},
         {"compensated", stats(r.compensated)},
         {"rmse_change_percent", num(percent_change(r.nominal.rmse, r.compensated.rmse))},
         {"std_change_percent", num(percent_change(r.nominal.std, r.compensated.std))}});
  j["residual_table"] = rows;
  json memory = json::array();
  for (const RestMemoryRow& m : ev.rest_memory)
    memory.push_back({{"joint", m.joint + 1},
                      {"static_samples", m.samples},
                      {"nominal_rmse", num(m.nominal_rmse)},
                      {"compensated_rmse", num(m.compensated_rmse)},
                      {"noise_floor", num(m.noise_floor)},
                      {"nominal_memory", num(m.nominal_memory)},
                      {"compensated_memory", num(m.compensated_memory)},
                      {"removed_share", num(m.removed_share)},
                      {"nominal_times_floor", num(m.nominal_times_floor)},
                      {"compensated_times_floor", num(m.compensated_times_floor)}});
  j["rest_memory"] = memory;
  j["excitation_rows"] = ev.excitation_rows;
  for (int m = 0; m < kModalityCount; ++m) {
    const std::string name = modality_name(static_cast<Modality>(m));
    if (ev.has_contacts) {
      const DetectionStats& d = ev.detection[m];
      j["detection"][name] = {{"events", d.events},
                              {"detected", d.detected},
                              {"median_latency_s", num(d.median_latency_s)},
                              {"median_force_at_detection_n", num(d.median_force_n)},
                              {"smallest_detected_peak_n", num(d.smallest_detected_peak_n)},
                              {"largest_missed_peak_n", num(d.largest_missed_peak_n)},
                              {"false_alarm_share", num(d.false_alarm_share)}};
      const ForceErrorStats& f = ev.force[m];
      j["force_error"][name] = {{"rows", f.count},
                                {"magnitude_rmse_n", num(f.magnitude_rmse)},
                                {"vector_rmse_n", num(f.vector_rmse)},
                                {"median_angle_deg", num(f.median_angle_deg)},
                                {"p90_angle_deg", num(f.p90_angle_deg)}};
    }
    if (ev.has_teaching)
      j["teaching"][name] = {{"rmse_nm", vec(ev.teaching.rmse[m])},
                             {"onset_rmse_nm", vec(ev.teaching.onset_rmse[m])}};
  }
  for (const TeachingLoop& l : ev.closed_loop) {
    if (!ev.has_closed_loop) break;
    j["closed_loop_teaching"].push_back(
        {{"mode", l.name},
         {"onsets", l.onsets},
         {"overshoots", l.overshoots},
         {"undershoots", l.undershoots},
         {"mean_overshoot_percent", num(l.mean_overshoot_percent)},
         {"mean_undershoot_percent", num(l.mean_undershoot_percent)},
         {"torque_rmse_nm", vec(l.torque_rmse)}});
  }
  if (ev.has_teaching)
    j["teaching"]["rows"] = {{"contact", ev.teaching.contact_rows},
                             {"onset", ev.teaching.onset_rows}};
  return j.dump(2);
}
TPF_UNOPTIMISED_WHEN_SANITIZED_END

}  // namespace tpf::offline
