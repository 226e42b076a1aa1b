// The estimator's contact flag: pads at once, torque-only alarms after a persistence test chosen
// for no false alarm on a contact-free log (all results simulated).
#include <gtest/gtest.h>

#include "tpf/estimation/persistence_test.hpp"
#include "tpf/estimation/transition_sigma.hpp"
#include "twin_fixture.hpp"

namespace {

using namespace tpf;
using namespace tpf::test;

/// Per sample: the combined external torque is outside its dead band on some joint.
Eigen::VectorXi torque_outside_band(TwinEstimator& est, const std::vector<ArmSample>& samples) {
  est.reset();
  Eigen::VectorXi e(static_cast<Eigen::Index>(samples.size()));
  for (std::size_t r = 0; r < samples.size(); ++r)
    e[static_cast<Eigen::Index>(r)] =
        (est.update(samples[r]).external.residual.array() != 0.0).any() ? 1 : 0;
  return e;
}

double contact_share(TwinEstimator& est, const std::vector<ArmSample>& samples) {
  est.reset();
  long on = 0;
  for (const ArmSample& s : samples)
    on += est.update(s).contact ? 1 : 0;
  return double(on) / double(samples.size());
}

// Calibrated on one contact-free log (seed 2) for no false alarm there (the evaluation's and
// `tpf calibrate`'s choice), the persistence silences the torque-only alarm on that log exactly,
// one cycle less does not — single samples alarm on percents of it (break-away transitions) — and
// the contact flag is on at every sample with a pad in contact.
TEST(ContactAlarm, PersistenceSilencesTheContactFreeLogAndPadsAlarmAtOnce) {
  const auto calibration = samples_from_log(twin_log("excitation", 2, 60));
  auto p = twin_parameters();
  {
    auto calibrating = std::make_unique<TwinEstimator>(twin_nominal(), twin_pads(), p);
    const auto sigma = calibrate_transition_sigma(*calibrating, calibration);
    p.nominal_sigma = p.fused_sigma = sigma.nominal;
  }
  auto single = std::make_unique<TwinEstimator>(twin_nominal(), twin_pads(), p);
  const Eigen::VectorXi outside = torque_outside_band(*single, calibration);
  p.torque_alarm_samples = persistence_for_false_alarm_rate(outside, 0.0, 80);
  EXPECT_GT(p.torque_alarm_samples, 1);
  EXPECT_LT(p.torque_alarm_samples, 80);
  auto persistent = std::make_unique<TwinEstimator>(twin_nominal(), twin_pads(), p);
  auto one_less_parameters = p;
  --one_less_parameters.torque_alarm_samples;
  auto one_less = std::make_unique<TwinEstimator>(twin_nominal(), twin_pads(), one_less_parameters);
  const double before = contact_share(*single, calibration);
  const double after = contact_share(*persistent, calibration);
  std::cout << "[ simulated ] contact-free excitation: torque-only alarms on " << 100 * before
            << " % of samples single, " << 100 * after << " % with " << p.torque_alarm_samples
            << " in a row\n";
  EXPECT_GT(before, 0.01);
  EXPECT_EQ(after, 0.0);
  EXPECT_GT(contact_share(*one_less, calibration), 0.0);

  const auto contacts = samples_from_log(twin_log("static-contacts", 3, 40));
  persistent->reset();
  long pad_rows = 0;
  for (const ArmSample& s : contacts) {
    const auto& out = persistent->update(s);
    if (!persistent->skin().any_contact()) continue;
    ++pad_rows;
    EXPECT_TRUE(out.contact);
  }
  EXPECT_GT(pad_rows, 1000);
}

}  // namespace
