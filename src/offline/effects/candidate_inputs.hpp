// What the candidate library needs from a first fit of the declared model.
#pragma once

#include <Eigen/Core>

namespace tpf::offline {

struct CandidateInputs {
  bool enabled = false;
  Eigen::VectorXd ripple_cycles;  ///< per joint: periods per output revolution (real), 0 = none
  Eigen::VectorXd ripple_motor_cycles;  ///< per joint: periods per motor revolution, 0 = none
  /// Per joint: the periods of ripple_cycles (ripple_motor_cycles) within the joint's range of
  /// motion; under 1 the candidate names no frequency and is ambiguous with its joint's offset
  /// and spring. Empty: every period in view.
  Eigen::VectorXd ripple_periods, ripple_motor_periods;
  Eigen::MatrixXd prediction_rate;  ///< d(declared prediction)/dt per sample and joint, or empty
  Eigen::MatrixXd abs_gravity;      ///< |G_j(q)| per sample and joint [N·m] (gravity_load)
  double reference_temperature = 25.0;  ///< °C
  /// Per joint: the declared fit's viscous coefficient b_j [N·m·s/rad], which the
  /// every-joint thermal candidate scales; empty = no every-joint thermal candidate.
  Eigen::VectorXd viscous;
};

}  // namespace tpf::offline
