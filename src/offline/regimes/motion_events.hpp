// Starts from rest and reversals of one joint's motion: how many motion onsets a log holds for
// the static-to-kinetic regime (a start opens its window) and for the reversal of friction.
#pragma once

#include <Eigen/Core>

#include "offline/regimes/regime.hpp"

namespace tpf::offline {

struct MotionEvents {
  int starts = 0;     ///< windows the regime labelling opens: |q̇| reaching the static threshold
  int reversals = 0;  ///< sign changes of q̇ between samples with |q̇| ≥ reversal_velocity
};

/// Counts the events of rows [begin, end) of one joint (t [s], q̇ [rad/s or m/s]): a start is a
/// sample label_regimes (with `regimes`, no residuals) labels static-to-kinetic after a sample it
/// does not; a reversal is a sample with |q̇| ≥ reversal_velocity whose sign differs from the
/// last such sample's (slower samples in between are skipped: a hysteresis against noise).
/// Throws tpf::Error when sizes differ or the range is outside the vectors.
MotionEvents count_motion_events(const Eigen::VectorXd& t, const Eigen::VectorXd& dq,
                                 Eigen::Index begin, Eigen::Index end, double reversal_velocity,
                                 const RegimeOptions& regimes = {});

}  // namespace tpf::offline
