// Start-up code of the estimator parameter file ("tpf-estimator"): every field of
// EstimatorParameters, required on load, written on save.

#include "tpf/estimation/estimator_parameter_file.hpp"

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "core/common/atomic_file.hpp"
#include "core/common/json_object.hpp"
#include "core/common/unoptimised_when_sanitized.hpp"

TPF_UNOPTIMISED_WHEN_SANITIZED_BEGIN

namespace tpf {
namespace {

using OrderedJson = nlohmann::ordered_json;  // saved in the struct's order, for people
using Bound = json::Object::Bound;

constexpr const char* kEstimatorFormat = "tpf-estimator";
constexpr int kEstimatorVersion = 3;  // 3: torques in N·m; 2: compensator_acceleration_limit
constexpr double kUnbounded = json::Object::kInfinity;
constexpr int kMaxSamples = 100'000'000;

OrderedJson ordered_array(const auto& v) {
  OrderedJson a = OrderedJson::array();
  for (Eigen::Index i = 0; i < v.size(); ++i)
    a.push_back(v[i]);
  return a;
}

// Per-joint limits, null for "no limit" (+∞; JSON has no infinity).
OrderedJson limits_array(const auto& v) {
  OrderedJson a = OrderedJson::array();
  for (Eigen::Index i = 0; i < v.size(); ++i)
    a.push_back(v[i] == std::numeric_limits<double>::infinity() ? OrderedJson(nullptr)
                                                                : OrderedJson(v[i]));
  return a;
}

const char* stop_policy_name(StopPolicy p) {
  return p == StopPolicy::KeepStale ? "keep_stale" : "hold_last_estimate";
}

/// A required number > 0 (and at most `hi`).
double positive(json::Object& o, const std::string& key, double hi = kUnbounded) {
  const double x = o.number(key, 0.0, hi);
  if (!(x > 0.0)) o.fail(key, "must be > 0 (positive), got 0");
  return x;
}

/// A required object (child() alone would accept an absent one as empty).
json::Object required_child(json::Object& o, const std::string& key) {
  if (!o.has(key)) o.fail(key, "missing");
  return o.child(key);
}

StaticFrictionSettings<double> read_static_friction(json::Object o) {
  StaticFrictionSettings<double> s;
  s.static_velocity = o.number("static_velocity", 0.0, 10.0);
  s.baseline_lead_s = o.number("baseline_lead_s", 0.0, 10.0);
  s.baseline_window_s = positive(o, "baseline_window_s", 10.0);
  if (!o.has("stop_policy")) o.fail("stop_policy", "missing");
  s.stop_policy = o.choice("stop_policy", "", {"hold_last_estimate", "keep_stale"}) == "keep_stale"
                      ? StopPolicy::KeepStale
                      : StopPolicy::HoldLastEstimate;
  o.finish();
  return s;
}

SkinSettings<double> read_skin(json::Object o) {
  SkinSettings<double> s;
  json::Object d = required_child(o, "detector");
  s.detector.cutoff_hz = positive(d, "cutoff_hz", 1e6);
  s.detector.on_level_kpa = positive(d, "on_level_kpa", 1e3);
  s.detector.off_level_kpa = d.number("off_level_kpa", 0.0, 1e3);
  if (!(s.detector.off_level_kpa < s.detector.on_level_kpa))
    d.fail("off_level_kpa", "must be below on_level_kpa (hysteresis)");
  s.detector.offset_time_constant_s = d.number("offset_time_constant_s", 0.0, 1e6);
  d.finish();
  s.force_gain = positive(o, "force_gain");
  s.full_scale_kpa = positive(o, "full_scale_kpa", 1e4);
  o.finish();
  return s;
}

ContactForceSettings<double> read_wrench(json::Object o) {
  ContactForceSettings<double> s;
  s.torque_noise_nm = positive(o, "torque_noise_nm");
  s.prior_relative = o.number("prior_relative", 0.0, kUnbounded);
  s.prior_floor_n = positive(o, "prior_floor_n");
  s.shear_relative = o.number("shear_relative", 0.0, kUnbounded);
  s.min_inverse_condition = o.number("min_inverse_condition", 0.0, 1.0);
  s.shear_regularisation = o.number("shear_regularisation", 0.0, kUnbounded);
  o.finish();
  return s;
}

}  // namespace

EstimatorParameters<double, Eigen::Dynamic> load_estimator_parameters(
    const std::filesystem::path& file, int joints) {
  json::Object top = json::Object::read_document(file, kEstimatorFormat, kEstimatorVersion);
  const double version = top.number("version", 0, 1e9);
  if (version < kEstimatorVersion)
    top.fail("version",
             "is " + std::to_string(static_cast<int>(version)) +
                 ": σ's and dead bands in the nominal model's effort unit (mA for a model of "
                 "currents); this tpf reads version 3, every torque in N*m. Convert the file with "
                 "`tpf upgrade --estimator FILE --params PARAMS` (PARAMS: the "
                 "version-1 parameter file it was calibrated with), or calibrate again");
  if (joints > 0) top.require_joints(joints);
  const int n = joints > 0 ? joints : top.integer("joints", 1, json::Object::kMaxArrayJoints);
  top.text("source", "");
  top.choice("torque_unit", "N*m", {"N*m"});

  EstimatorParameters<double, Eigen::Dynamic> p;
  p.resize(n);
  p.sample_period_s = positive(top, "sample_period_s", 1.0);
  p.max_gap_factor = top.number("max_gap_factor", 1.0, 1e6);
  p.position_margin_rad = top.number("position_margin_rad", 0.0, 100.0);
  p.acceleration_cutoff_hz = positive(top, "acceleration_cutoff_hz", 1e6);
  p.acceleration_damping = positive(top, "acceleration_damping", 100.0);
  p.frozen_limit_samples = top.integer("frozen_limit_samples", 0, kMaxSamples);
  p.stuck_pad_limit_samples = top.integer("stuck_pad_limit_samples", 0, kMaxSamples);
  p.static_friction = read_static_friction(required_child(top, "static_friction"));
  p.skin = read_skin(required_child(top, "skin"));
  p.wrench = read_wrench(required_child(top, "wrench"));
  top.joint_vector("nominal_sigma", p.nominal_sigma, true, Bound::kNonNegative);
  top.joint_vector("fused_sigma", p.fused_sigma, true, Bound::kNonNegative);
  p.dead_band_factor = top.number("dead_band_factor", 0.0, 1e3);
  p.torque_alarm_samples = top.integer("torque_alarm_samples", 1, kMaxSamples);
  top.joint_vector("static_dead_band", p.static_dead_band, true, Bound::kNonNegative);
  top.joint_limits("compensator_speed_limit", p.compensator_speed_limit);
  top.joint_limits("compensator_acceleration_limit", p.compensator_acceleration_limit);
  // Optional (files calibrated before the gate hold none): the default, 0.
  p.compensator_min_held_out_gain =
      top.number("compensator_min_held_out_gain", p.compensator_min_held_out_gain, -1e3, 1.0);
  top.finish();
  return p;
}

void save_estimator_parameters(const std::filesystem::path& file,
                               const EstimatorParameters<double, Eigen::Dynamic>& p,
                               const std::string& source) {
  p.check_joint_count(p.joint_count());
  OrderedJson j;
  j["format"] = kEstimatorFormat;
  j["version"] = kEstimatorVersion;
  j["joints"] = p.joint_count();
  if (!source.empty()) j["source"] = source;
  j["torque_unit"] = "N*m";
  j["sample_period_s"] = p.sample_period_s;
  j["max_gap_factor"] = p.max_gap_factor;
  j["position_margin_rad"] = p.position_margin_rad;
  j["acceleration_cutoff_hz"] = p.acceleration_cutoff_hz;
  j["acceleration_damping"] = p.acceleration_damping;
  j["frozen_limit_samples"] = p.frozen_limit_samples;
  j["stuck_pad_limit_samples"] = p.stuck_pad_limit_samples;
  const StaticFrictionSettings<double>& f = p.static_friction;
  j["static_friction"] = {{"static_velocity", f.static_velocity},
                          {"baseline_lead_s", f.baseline_lead_s},
                          {"baseline_window_s", f.baseline_window_s},
                          {"stop_policy", stop_policy_name(f.stop_policy)}};
  const PadDetectorSettings<double>& d = p.skin.detector;
  j["skin"] = {{"detector",
                {{"cutoff_hz", d.cutoff_hz},
                 {"on_level_kpa", d.on_level_kpa},
                 {"off_level_kpa", d.off_level_kpa},
                 {"offset_time_constant_s", d.offset_time_constant_s}}},
               {"force_gain", p.skin.force_gain},
               {"full_scale_kpa", p.skin.full_scale_kpa}};
  const ContactForceSettings<double>& w = p.wrench;
  j["wrench"] = {{"torque_noise_nm", w.torque_noise_nm},
                 {"prior_relative", w.prior_relative},
                 {"prior_floor_n", w.prior_floor_n},
                 {"shear_relative", w.shear_relative},
                 {"min_inverse_condition", w.min_inverse_condition},
                 {"shear_regularisation", w.shear_regularisation}};
  j["nominal_sigma"] = ordered_array(p.nominal_sigma);
  j["fused_sigma"] = ordered_array(p.fused_sigma);
  j["dead_band_factor"] = p.dead_band_factor;
  j["torque_alarm_samples"] = p.torque_alarm_samples;
  j["static_dead_band"] = ordered_array(p.static_dead_band);
  j["compensator_speed_limit"] = limits_array(p.compensator_speed_limit);
  j["compensator_acceleration_limit"] = limits_array(p.compensator_acceleration_limit);
  j["compensator_min_held_out_gain"] = p.compensator_min_held_out_gain;
  json::require_finite(j, file);
  write_file_atomically(file, j.dump(2) + "\n");
}

}  // namespace tpf

TPF_UNOPTIMISED_WHEN_SANITIZED_END
