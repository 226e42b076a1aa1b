#include "arm/estimator_hook.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "tpf/common/error.hpp"
#include "tpf/estimation/estimator_status.hpp"

namespace tpf::arm {

namespace {

/// The core's estimator set-up for the arm, from the files; `description` says what was loaded.
EstimatorSetup<kArmJoints> load_setup(const EstimatorFiles& f, std::string& description) {
  EstimatorSetup<kArmJoints> setup = load_estimator_setup<kArmJoints>(f);
  if (setup.nominal.effort_unit != "mA")
    throw Error::at(f.params, 0, "effort_unit",
                    "is \"" + setup.nominal.effort_unit +
                        "\"; the loop measures motor currents in mA (identify on an i<j> log)");
  description = "estimator: " + f.params + ", " + std::to_string(setup.pads.size()) +
                " pads, parameters " + f.estimator + ", " + describe(setup.weights) +
                (f.weights.empty() ? "" : " (" + f.weights + ")");
  return setup;
}

}  // namespace

EstimatorHook::EstimatorHook(const EstimatorFiles& files) {
  const EstimatorSetup<kArmJoints> setup = load_setup(files, description_);
  if (setup.weights.layout == CompensatorLayout::None)
    estimator_ = make_estimator<kArmJoints, kArmPads, NoCompensator>(setup);
  else
    estimator_ = make_estimator<kArmJoints, kArmPads, PerJointTcn<float, 16>>(setup);
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
  output_ = &std::visit([this](auto& e) -> const Output& { return e->update(input_); }, estimator_);

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

}  // namespace tpf::arm
