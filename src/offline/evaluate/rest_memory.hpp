// The friction memory at rest: what the compensator removes of the static residual, and what it
// leaves above the effort's noise floor (the limit no model of the motion can pass).
#pragma once

#include <vector>

#include "offline/evaluate/residual_table.hpp"

namespace tpf::offline {

/// One joint's static residual split into noise and memory, in the recordings' unit (mA for
/// currents). memory = √(rmse² − floor²) (0 where the RMSE is at the floor).
struct RestMemoryRow {
  int joint = 0;                         ///< 0-based
  std::size_t samples = 0;               ///< static samples behind the RMSEs
  double nominal_rmse = 0.0;             ///< static residual of the nominal model
  double compensated_rmse = 0.0;         ///< static residual with the compensator
  double noise_floor = 0.0;              ///< white noise of the effort at rest
  double nominal_memory = 0.0;           ///< the part above the floor, nominal
  double compensated_memory = 0.0;       ///< the part above the floor, compensated
  double removed_share = 0.0;            ///< 1 − compensated_memory / nominal_memory
  double nominal_times_floor = 0.0;      ///< nominal_rmse / noise_floor
  double compensated_times_floor = 0.0;  ///< compensated_rmse / noise_floor
};

/// The effort's white noise at rest per joint: std of the nominal residual's sample-to-sample
/// change over pairs of consecutive static samples, divided by √2 (a slowly varying memory
/// cancels in the difference; white noise of σ gives a difference of σ·√2). NaN for a joint
/// that never rests for two samples.
Eigen::VectorXd rest_noise_floor(const std::vector<ResidualRecording>& recordings,
                                 const RegimeOptions& options = {});

/// One row per joint from Table I's static rows and the noise floor of the same recordings.
std::vector<RestMemoryRow> rest_memory(const std::vector<ResidualRow>& table,
                                       const Eigen::VectorXd& noise_floor);

}  // namespace tpf::offline
