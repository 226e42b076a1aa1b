// The one labelling of samples into motion regimes that every offline tool uses.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string_view>
#include <vector>

namespace tpf::offline {

/// Motion regime of one joint at one sample.
enum class Regime : std::uint8_t { Static, StaticToKinetic, Moving, Invalid };
inline constexpr int kRegimeCount = 4;

/// "static", "static-to-kinetic", "moving", "invalid".
std::string_view regime_name(Regime regime);

/// 0, 1, 2 for Static, StaticToKinetic, Moving: the slot of a valid regime in per-regime tables
/// (the order of regime_name and of a weight file's held-out gains).
constexpr int regime_index(Regime regime) {
  return static_cast<int>(regime);
}

struct RegimeOptions {
  double static_velocity = 1e-4;        ///< rad/s; |dq| below this is static (the original's value)
  double max_transition_s = 0.2;        ///< s; a static-to-kinetic window never lasts longer
  double fallback_transition_s = 0.07;  ///< s; window length when no compensated residual is given
  double gap_factor = 1.5;              ///< a step > gap_factor · median step is a gap
};

/// Labels the samples of one joint:
/// - Invalid where t or dq is NaN;
/// - Static where |dq| < static_velocity;
/// - StaticToKinetic from the sample k0 where |dq| reaches the threshold right after a static
///   sample (same segment: no gap, no NaN between them) until the residuals of the nominal and
///   compensated models meet: the first k > k0 with |d_k| ≤ meet_tolerance or sign(d_k) ≠
///   sign(d_k0), d = r_nominal − r_compensated (that sample is Moving). Without both residuals the
///   window is fallback_transition_s long. Either way it holds only samples with t_k − t_k0 <
///   max_transition_s and ends early at a gap, a NaN or a return below the threshold;
/// - Moving otherwise (including motion at the start of a log, with no static stretch before).
/// Throws tpf::Error when sizes differ.
std::vector<Regime> label_regimes(const Eigen::VectorXd& t, const Eigen::VectorXd& dq,
                                  const RegimeOptions& options = {},
                                  const Eigen::VectorXd* residual_nominal = nullptr,
                                  const Eigen::VectorXd* residual_compensated = nullptr,
                                  double meet_tolerance = 0.0);

}  // namespace tpf::offline
