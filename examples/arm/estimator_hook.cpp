#include "arm/estimator_hook.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "tpf/common/error.hpp"
#include "tpf/estimation/estimator_status.hpp"
#include "tpf/model/effort_unit.hpp"

namespace tpf::arm {

namespace {

/// The core's estimator set-up for the arm, from the files; `description` says what was loaded.
EstimatorSetup<kArmJoints> load_setup(const EstimatorFiles& f, std::string& description) {
  EstimatorSetup<kArmJoints> setup = load_estimator_setup<kArmJoints>(f);
  description = "estimator: " + f.params + ", " + std::to_string(setup.pads.size()) +
                " pads, parameters " + f.estimator + ", " + describe(setup.weights) +
                (f.weights.empty() ? "" : " (" + f.weights + ")");
  return setup;
}

}  // namespace

EstimatorHook::EstimatorHook(const EstimatorFiles& files) {
  const EstimatorSetup<kArmJoints> setup = load_setup(files, description_);
  model_ = setup.nominal.model;
  if (setup.weights.layout == CompensatorLayout::None)
    estimator_ = make_estimator<kArmJoints, kArmPads, NoCompensator>(setup);
  else
    estimator_ = make_estimator<kArmJoints, kArmPads, PerJointTcn<BFloat16Weights, 16>>(setup);
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
  // The drives report current [mA]; the estimator computes in N·m.
  input_.effort = torque_from_current(model_, input_.effort);
  for (int k = 0; k < kPads; ++k)
    input_.pressure[k] =
        s.pads_valid && static_cast<std::size_t>(k) < s.pads ? static_cast<double>(s.p[k]) : nan;
  output_ = &std::visit([this](auto& e) -> const Output& { return e->update(input_); }, estimator_);

  record_estimate(*output_);
  count(*output_);
  if (trace_.size() < trace_.capacity()) {
    EstimateRecord r;
    r.t = s.t;
    r.status = estimate_.status;
    r.contact_pad = estimate_.contact_pad;
    r.external_torque_nm =
        estimate_.present ? output_->external.torque : JointVector<double, kJoints>::Constant(nan);
    r.normal_force_n = estimate_.present ? -output_->wrench.force_contact.z() : nan;
    trace_.push_back(r);
  }
}

void EstimatorHook::record_estimate(const Output& out) noexcept {
  // A skipped cycle has no estimate: not present (NaN in the log), contact_pad −1.
  const bool skipped = out.status & (kStatusNonFiniteInput | kStatusStaleTime);
  estimate_.present = !skipped;
  estimate_.status = out.status;
  estimate_.contact = !skipped && out.contact;
  estimate_.contact_pad = skipped ? -1 : out.wrench.pad;
  for (int j = 0; j < kJoints; ++j)
    estimate_.external_torque_nm[static_cast<std::size_t>(j)] = out.external.torque[j];
  for (int a = 0; a < 3; ++a)
    estimate_.force_world_n[static_cast<std::size_t>(a)] =
        out.wrench.pad >= 0 ? out.wrench.force_world[a] : 0.0;
}

void EstimatorHook::count(const Output& out) noexcept {
  EstimatorStatistics& st = statistics_;
  ++st.updates;
  for (int b = 0; b < EstimatorStatistics::kStatusBits; ++b)
    if (out.status & (1u << b)) ++st.status_bit[static_cast<std::size_t>(b)];
  if (estimate_.present) {
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
}

}  // namespace tpf::arm
