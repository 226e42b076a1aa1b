// Adam optimiser over a flat parameter vector.
#pragma once

#include <Eigen/Core>

namespace tpf::offline {

/// Adam (Kingma & Ba 2015): with g the gradient and n the step count,
///   m ← β₁m + (1 − β₁)g,  v ← β₂v + (1 − β₂)g²,
///   θ ← θ − α·(m/(1 − β₁ⁿ)) / (√(v/(1 − β₂ⁿ)) + ε).
class AdamOptimizer {
 public:
  struct Settings {
    double learning_rate = 2e-3;
    double beta1 = 0.9;
    double beta2 = 0.999;
    double epsilon = 1e-8;
  };

  AdamOptimizer(Eigen::Index size, const Settings& settings);

  double learning_rate() const { return settings_.learning_rate; }
  void set_learning_rate(double rate) { settings_.learning_rate = rate; }

  /// One update of `parameters` along `gradient` (same size).
  void step(Eigen::VectorXd& parameters, const Eigen::VectorXd& gradient);

 private:
  Settings settings_;
  Eigen::VectorXd m_;
  Eigen::VectorXd v_;
  long steps_ = 0;
};

}  // namespace tpf::offline
