// The 4-DoF arm of data/ and seeded random states, shared by the core tests.
#pragma once

#include <algorithm>
#include <cmath>
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

/// The angle between two vectors, degrees: acos(â·b̂).
inline double angle_deg(const Vector3<double>& a, const Vector3<double>& b) {
  return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)) * 180.0 / M_PI;
}

inline const Arm& arm() {
  static const Arm model = load_robot<double, kJoints>(data_path("arm4.robot.json"));
  return model;
}

/// A uniform joint vector of an N-joint arm in [−scale, scale] from `rng`.
template <int N>
JointVector<double, N> random_vector(std::mt19937_64& rng, double scale) {
  std::uniform_real_distribution<double> u(-scale, scale);
  JointVector<double, N> v;
  for (int j = 0; j < N; ++j)
    v(j) = u(rng);
  return v;
}

/// Seeded uniform vectors in [−scale, scale] of the 4-DoF arm.
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
