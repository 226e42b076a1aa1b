#include "offline/compensator_training/adam.hpp"

#include <cmath>

namespace tpf::offline {

AdamOptimizer::AdamOptimizer(Eigen::Index size, const Settings& settings)
    : settings_(settings), m_(Eigen::VectorXd::Zero(size)), v_(Eigen::VectorXd::Zero(size)) {}

void AdamOptimizer::step(Eigen::VectorXd& parameters, const Eigen::VectorXd& gradient) {
  ++steps_;
  const double b1 = settings_.beta1, b2 = settings_.beta2;
  m_ = b1 * m_ + (1.0 - b1) * gradient;
  v_ = b2 * v_ + (1.0 - b2) * gradient.cwiseAbs2();
  const double m_scale = 1.0 / (1.0 - std::pow(b1, static_cast<double>(steps_)));
  const double v_scale = 1.0 / (1.0 - std::pow(b2, static_cast<double>(steps_)));
  parameters.array() -= settings_.learning_rate * (m_.array() * m_scale) /
                        ((v_.array() * v_scale).sqrt() + settings_.epsilon);
}

}  // namespace tpf::offline
