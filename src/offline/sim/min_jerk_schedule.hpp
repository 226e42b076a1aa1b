// Joint reference made of rests and minimum-jerk moves, per joint independently.
//   q(t) = q0 + (q1 − q0)·s(τ),  s(τ) = 10τ³ − 15τ⁴ + 6τ⁵,  τ = (t − t0)/(t1 − t0)
// The peak speed of a move is 1.875·|q1 − q0|/(t1 − t0).
#pragma once

#include <cstddef>
#include <vector>

#include "offline/sim/scenario.hpp"

namespace tpf::offline {

class MinJerkSchedule {
 public:
  struct Segment {
    double t0, t1, q0, q1;  ///< q0 == q1 is a rest
  };

  /// Every joint rests at `start` (one entry per joint) until moves are appended.
  explicit MinJerkSchedule(const TwinVector& start)
      : segments_(static_cast<std::size_t>(start.size())),
        cursor_(static_cast<std::size_t>(start.size()), 0),
        end_t_(static_cast<std::size_t>(start.size()), 0.0),
        end_q_(start) {}

  /// Appends a move of joint j to q1 lasting `duration` (a rest when q1 equals the last target).
  void append(int j, double q1, double duration);
  /// Time at which joint j's schedule ends.
  double end_time(int j) const { return end_t_[static_cast<std::size_t>(j)]; }
  /// Last target of joint j.
  double end_position(int j) const { return end_q_[j]; }

  /// Reference at time t (t must not decrease between calls: cursors advance monotonically).
  void evaluate(double t, TwinVector& q, TwinVector& dq);

 private:
  std::vector<std::vector<Segment>> segments_;  ///< per joint
  std::vector<std::size_t> cursor_;
  std::vector<double> end_t_;
  TwinVector end_q_;
};

}  // namespace tpf::offline
