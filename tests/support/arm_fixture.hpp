// The 4-DoF arm of data/ and seeded random states, shared by the core tests.
#pragma once

#include <random>

#include "tpf/core.hpp"

namespace tpf::test {

inline constexpr int kJoints = 4;
using Arm = Model<double, kJoints>;
using ArmData = Data<double, kJoints>;
using Vec = JointVector<double, kJoints>;

inline std::string data_path(const std::string& name) {
  return std::string(TPF_TEST_DATA_DIR) + "/" + name;
}

inline const Arm& arm() {
  static const Arm model = load_robot<double, kJoints>(data_path("arm4.robot.json"));
  return model;
}

/// Seeded uniform vectors in [−scale, scale].
class RandomStates {
 public:
  explicit RandomStates(unsigned seed) : rng_(seed) {}
  Vec vector(double scale) {
    Vec v;
    for (int i = 0; i < kJoints; ++i)
      v(i) = std::uniform_real_distribution<double>(-scale, scale)(rng_);
    return v;
  }
  Vector3<double> point(double scale) {
    Vector3<double> v;
    for (int i = 0; i < 3; ++i)
      v(i) = std::uniform_real_distribution<double>(-scale, scale)(rng_);
    return v;
  }

 private:
  std::mt19937_64 rng_;
};

}  // namespace tpf::test
