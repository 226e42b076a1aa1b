// Joint reference made of rests and minimum-jerk moves, per joint independently.
//   q(t) = q0 + (q1 − q0)·s(τ),  s(τ) = 10τ³ − 15τ⁴ + 6τ⁵,  τ = (t − t0)/(t1 − t0)
// The peak speed of a move is 1.875·|q1 − q0|/(t1 − t0).
#pragma once

#include <vector>

#include "offline/sim/scenario.hpp"

namespace tpf::offline {

class MinJerkSchedule {
 public:
  struct Segment {
    double t0, t1, q0, q1;  ///< q0 == q1 is a rest
  };

  explicit MinJerkSchedule(const TwinVector& start) : end_q_(start) {}

  /// Appends a move of joint j to q1 lasting `duration` (a rest when q1 equals the last target).
  void append(int j, double q1, double duration);
  /// Time at which joint j's schedule ends.
  double end_time(int j) const { return end_t_[j]; }
  /// Last target of joint j.
  double end_position(int j) const { return end_q_[j]; }

  /// Reference at time t (t must not decrease between calls: cursors advance monotonically).
  void evaluate(double t, TwinVector& q, TwinVector& dq);

 private:
  std::vector<Segment> segments_[kTwinJoints];
  std::size_t cursor_[kTwinJoints] = {};
  double end_t_[kTwinJoints] = {};
  TwinVector end_q_;
};

}  // namespace tpf::offline
