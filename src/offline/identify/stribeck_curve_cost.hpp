// The residuals of one joint's Stribeck curve on its moving samples, as one Ceres cost with an
// analytic Jacobian (fit_stribeck's problem).
#pragma once

#include <ceres/ceres.h>

#include <Eigen/Core>
#include <cmath>
#include <utility>

namespace tpf::offline {

/// The curve's residuals on every moving sample as one residual block (per-sample blocks would
/// spend the fit in Ceres' bookkeeping), with the analytic Jacobian. The three vectors (equal
/// sizes, |q̇| > 0) must outlive the cost. Parameters x = [τ_c, τ_s, q̇_s, δ, b, α_c, α_v]; with
/// u = |q̇|/q̇_s, E = exp(−u^δ), s = sgn(q̇) and L = τ_c + α_c|G| + (τ_s − τ_c)·E:
///   r = s·L + (b + α_v|G|)·q̇ − f,
///   ∂r/∂τ_c = s(1 − E), ∂r/∂τ_s = s·E, ∂r/∂q̇_s = s(τ_s − τ_c)·E·δ·u^δ/q̇_s,
///   ∂r/∂δ = −s(τ_s − τ_c)·E·u^δ·ln u, ∂r/∂b = q̇, ∂r/∂α_c = s|G|, ∂r/∂α_v = |G|·q̇.
/// With a Cauchy scale c > 0 each residual is r̃ = sgn(r)·√ρ(r²), ρ(s) = c²·ln(1 + s/c²), so the
/// cost ½Σr̃² is the Cauchy loss of every sample (a block-wide Ceres loss would robustify the
/// sum), and ∂r̃/∂x = ρ'(r²)·|r|/√ρ(r²)·∂r/∂x with ρ'(s) = 1/(1 + s/c²) (1 at r = 0).
class StribeckCurveCost final : public ceres::CostFunction {
 public:
  static constexpr int kParameters = 7;

  StribeckCurveCost(const Eigen::VectorXd& dq, const Eigen::VectorXd& abs_gravity,
                    const Eigen::VectorXd& target, double cauchy_scale = 0.0)
      : dq_(dq), abs_gravity_(abs_gravity), target_(target), cauchy_scale_(cauchy_scale) {
    set_num_residuals(static_cast<int>(dq.size()));
    mutable_parameter_block_sizes()->push_back(kParameters);
  }

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    const double* x = parameters[0];
    const double drop = x[1] - x[0];
    for (Eigen::Index k = 0; k < dq_.size(); ++k) {
      const double v = dq_[k], g = abs_gravity_[k];
      const double sign = v > 0 ? 1.0 : -1.0;
      const double u = std::abs(v) / x[2];
      const double u_delta = std::pow(u, x[3]);
      const double e = std::exp(-u_delta);
      const double r = sign * (x[0] + x[5] * g + drop * e) + (x[4] + x[6] * g) * v - target_[k];
      const auto [robust, slope] = robustified(r);
      residuals[k] = robust;
      if (jacobians == nullptr || jacobians[0] == nullptr) continue;
      double* row = jacobians[0] + k * kParameters;
      row[0] = slope * sign * (1.0 - e);
      row[1] = slope * sign * e;
      row[2] = slope * sign * drop * e * x[3] * u_delta / x[2];
      row[3] = u > 0 ? -slope * sign * drop * e * u_delta * std::log(u) : 0.0;
      row[4] = slope * v;
      row[5] = slope * sign * g;
      row[6] = slope * g * v;
    }
    return true;
  }

 private:
  // r̃ and dr̃/dr (r itself and 1 without a Cauchy scale).
  std::pair<double, double> robustified(double r) const {
    if (!(cauchy_scale_ > 0) || r == 0.0) return {r, 1.0};
    const double c2 = cauchy_scale_ * cauchy_scale_, ratio = r * r / c2;
    const double root = std::sqrt(c2 * std::log1p(ratio));
    return {std::copysign(root, r), std::abs(r) / ((1.0 + ratio) * root)};
  }

  const Eigen::VectorXd& dq_;
  const Eigen::VectorXd& abs_gravity_;
  const Eigen::VectorXd& target_;
  double cauchy_scale_;
};

}  // namespace tpf::offline
