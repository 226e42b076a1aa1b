// The original work's Table I: RMSE and std of the current residual per joint in the static and
// static-to-kinetic states, nominal model against the TCN-compensated one.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "offline/regimes/regime_stats.hpp"

namespace tpf::offline {

/// One contact-free recording: per row t [s], q̇ (T × N), the nominal residual τ_res and the
/// compensated residual τ_res − τ_TCN (T × N, one unit: Table I passes the log's, mA). On
/// contact-free data both are estimation errors (the true external torque is 0). NaN rows are
/// skipped.
struct ResidualRecording {
  Eigen::VectorXd t;
  Eigen::MatrixXd dq;
  Eigen::MatrixXd nominal;
  Eigen::MatrixXd compensated;
};

struct ResidualRow {
  int joint = 0;  ///< 0-based; −1 = all joints pooled
  Regime regime = Regime::Static;
  ResidualStats nominal;
  ResidualStats compensated;
};

/// Rows per joint (then all joints pooled) and per regime (Static, StaticToKinetic, Moving).
/// Regimes come from label_regimes per recording and joint with both residuals: the
/// static-to-kinetic window runs from |q̇_j| crossing options.static_velocity after rest until the
/// two residuals meet (|d| ≤ meet_tolerance[j] or d changes sign, d = nominal − compensated),
/// at most options.max_transition_s. Throws tpf::Error on inconsistent sizes.
std::vector<ResidualRow> residual_table(const std::vector<ResidualRecording>& recordings,
                                        const Eigen::VectorXd& meet_tolerance,
                                        const RegimeOptions& options = {});

}  // namespace tpf::offline
