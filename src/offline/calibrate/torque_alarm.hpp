// The persistence of the estimator's torque-only contact alarm, calibrated on a contact-free log.
#pragma once

#include "offline/replay/estimator_trace.hpp"

namespace tpf::offline {

/// False-alarm rate the torque-only contact alarm's persistence is chosen for, per contact-free
/// row of the calibration log, and the longest persistence allowed (0.2 s at 400 Hz). Zero: the
/// shortest persistence that raises no alarm anywhere on the contact-free calibration log (its
/// longest out-of-band run + 1 cycle). Any positive rate is a false contact every few seconds at
/// 400 Hz (0.1 % = 24 alarmed cycles a minute), which a controller reacting to contact cannot use.
inline constexpr double kTorqueAlarmFalseAlarmRate = 0.0;
inline constexpr int kTorqueAlarmMaxSamples = 80;

/// The torque-only alarm's persistence for kTorqueAlarmFalseAlarmRate on the trace of a
/// contact-free log (replay_estimator with the calibrated bands; rows without a pad in
/// contact): persistence_for_false_alarm_rate of "the combined estimate is outside its dead band
/// on some joint" over those rows.
int calibrate_torque_alarm(const EstimatorTrace& tr);

}  // namespace tpf::offline
