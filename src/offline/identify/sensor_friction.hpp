// The friction reference of a log with joint torque sensors: what the drive spends between the
// motor current and the sensor behind the gear, effort − (τ_sensor + I_a·q̈) [N·m], is the
// friction itself (no rigid-body model in between). identify uses it with
// IdentifyOptions::friction_from_sensor.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "offline/log/log.hpp"
#include "offline/samples/joint_samples.hpp"

namespace tpf::offline {

struct SensorFrictionReference {
  /// Per sample and joint, what the friction target subtracts from the effort: τ_sensor +
  /// I_a·q̈ [N·m] where the joint's sensor varies in the sample's file (NaN in its other files), the
  /// rigid-body prediction on joints whose sensor varies nowhere.
  Eigen::MatrixXd reference;
  std::vector<bool> from_sensor;     ///< per joint
  Eigen::VectorXd coulomb, viscous;  ///< linear start per joint [N·m] (NaN: not from sensor)
  std::string note;                  ///< which joints, how many samples
};

/// The reference for `samples` of `log`. `armature` [kg·m²] per joint (0 where unknown), `rigid`
/// the rigid-body prediction [N·m]. The linear start is the
/// least squares of effort − reference on [sgn q̇, q̇] over the moving samples with a reference.
SensorFrictionReference sensor_friction_reference(const Log& log, const JointSamples& samples,
                                                  const Eigen::VectorXd& armature,
                                                  const Eigen::MatrixXd& rigid);

}  // namespace tpf::offline
