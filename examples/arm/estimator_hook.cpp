#include "arm/estimator_hook.hpp"

#include <cmath>
#include <cstdio>
#include <limits>

#include "offline/log/read_log.hpp"
#include "offline/training/estimator_samples.hpp"
#include "tpf/common/error.hpp"
#include "tpf/estimation/estimator_status.hpp"
#include "tpf/estimation/nominal_model.hpp"
#include "tpf/skin/pad_layout.hpp"

namespace tpf::arm {

namespace {

/// The offline tools' estimator set-up for the arm, from the files.
offline::ArmEstimatorSetup load_setup(const EstimatorFiles& f, std::string& description) {
  offline::ArmEstimatorSetup setup;
  setup.nominal = load_nominal_model<offline::kArmJoints>(f.params, f.robot);
  if (setup.nominal.effort_unit != "mA")
    throw Error::at(f.params, 0, "effort_unit",
                    "is \"" + setup.nominal.effort_unit +
                        "\"; the loop measures motor currents in mA (identify on an i<j> log)");
  setup.pads = load_pads(f.pads, setup.nominal.model);
  description = "estimator: " + f.params + ", " + std::to_string(setup.pads.size()) + " pads";
  if (!f.weights.empty()) {
    setup.weight_files = offline::compensator_files(f.weights, setup.layout);
    description += setup.layout == offline::CompensatorLayout::PerJoint
                       ? ", one friction network per joint (" + f.weights + ")"
                       : ", friction network " + f.weights;
  } else {
    description += ", no friction compensator";
  }
  if (!f.calibration_log.empty()) {
    const offline::Log log = offline::read_log(f.calibration_log);
    setup.parameters = offline::arm_estimator_parameters(offline::estimate_sensor_noise(log),
                                                         f.pad_gain_kpa_per_n);
    offline::calibrate_arm_sigma(
        setup, offline::estimator_samples<offline::kArmJoints, offline::kArmPads>(log),
        f.calibration_log);
    description += ", dead bands from " + f.calibration_log;
  } else {
    offline::SensorNoise noise;
    noise.effort.setConstant(f.effort_noise_ma);
    noise.pad_kpa = f.pad_noise_kpa;
    setup.parameters = offline::arm_estimator_parameters(noise, f.pad_gain_kpa_per_n);
    char noise_text[96];
    std::snprintf(noise_text, sizeof noise_text, ", dead bands from the noise (%g mA, %g kPa)",
                  f.effort_noise_ma, f.pad_noise_kpa);
    description += noise_text;
  }
  return setup;
}

}  // namespace

EstimatorHook::EstimatorHook(const EstimatorFiles& files) {
  step_ = offline::make_arm_estimator_step(load_setup(files, description_));
  output_ = &empty_;
  trace_.reserve(files.trace_capacity);
}

void EstimatorHook::update(const CycleSample& s) noexcept {
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  input_.t = s.t;
  for (int j = 0; j < kJoints; ++j) {
    const bool have = s.motors_valid && static_cast<std::size_t>(j) < s.joints;
    input_.q[j] = have ? s.q[j] : nan;
    input_.dq[j] = have ? s.dq[j] : nan;
    input_.effort[j] = have ? s.i[j] : nan;
  }
  for (int k = 0; k < kPads; ++k)
    input_.pressure[k] =
        s.pads_valid && static_cast<std::size_t>(k) < s.pads ? static_cast<double>(s.p[k]) : nan;
  output_ = &step_(input_);

  EstimatorStatistics& st = statistics_;
  const Output& out = *output_;
  ++st.updates;
  for (int b = 0; b < EstimatorStatistics::kStatusBits; ++b)
    if (out.status & (1u << b)) ++st.status_bit[static_cast<std::size_t>(b)];
  const bool skipped = out.status & (kStatusNonFiniteInput | kStatusStaleTime);
  if (!skipped) {
    if (out.wrench.pad >= 0) ++st.contact_cycles;
    if (out.state != ContactState::Dynamic) ++st.static_cycles;
  }
  if (out.status == kStatusOk) {
    ++st.clean;
    if (!out.external.torque.allFinite()) ++st.non_finite_estimates;
    for (int j = 0; j < kJoints; ++j)
      st.max_abs_torque_nm[static_cast<std::size_t>(j)] = std::max(
          st.max_abs_torque_nm[static_cast<std::size_t>(j)], std::abs(out.external.torque[j]));
  }
  if (trace_.size() < trace_.capacity()) {
    EstimateRecord r;
    r.t = s.t;
    r.status = out.status;
    r.contact_pad = skipped ? -1 : out.wrench.pad;  // a skipped cycle has no estimate: NaN
    r.external_torque_nm =
        skipped ? JointVector<double, kJoints>::Constant(nan) : out.external.torque;
    r.normal_force_n = skipped ? nan : -out.wrench.force_contact.z();
    trace_.push_back(r);
  }
}

const char* estimator_status_name(int bit) noexcept {
  static constexpr const char* names[EstimatorStatistics::kStatusBits] = {
      "non-finite input (skipped)", "stale time (skipped)", "time gap",
      "position out of range",      "pad data invalid",     "wrench unobservable",
      "acceleration estimated",     "frozen input",         "pad stuck"};
  return bit >= 0 && bit < EstimatorStatistics::kStatusBits ? names[bit] : "unknown";
}

}  // namespace tpf::arm
