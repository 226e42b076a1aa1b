#include "offline/calibrate/torque_alarm.hpp"

#include <cmath>
#include <vector>

#include "tpf/estimation/persistence_test.hpp"

namespace tpf::offline {

int calibrate_torque_alarm(const EstimatorTrace& tr) {
  const Eigen::VectorXi outside = any_joint_outside_band(combined_external(tr));
  std::vector<int> free;
  for (Eigen::Index k = 0; k < tr.rows(); ++k)
    if (std::isfinite(tr.t[k]) && tr.contact[k] == 0) free.push_back(outside[k]);
  return persistence_for_false_alarm_rate(
      Eigen::Map<const Eigen::VectorXi>(free.data(), static_cast<Eigen::Index>(free.size())),
      kTorqueAlarmFalseAlarmRate, kTorqueAlarmMaxSamples);
}

}  // namespace tpf::offline
