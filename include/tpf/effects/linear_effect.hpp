// The run-time torque of an effect that is linear in its parameters: per joint, its basis
// functions (the regressor columns diagnose fits) times its coefficients. One definition of the
// columns serves the fit and the run time, so the two agree by construction.
#pragma once

#include "tpf/effects/effect_input.hpp"

namespace tpf {

/// τ_j += Σ_c φ_c(x)·θ_jc for every joint j, with φ = Effect::basis(x, j, ·) and θ_j =
/// effect.coefficients(j, ·) (effect.columns() of each). A joint whose θ_j is all zero (the effect
/// not added there) is skipped: its basis is not evaluated. Allocation-free at a fixed joint count
/// (at Eigen::Dynamic the two column buffers are allocated).
template <typename Effect, typename S, int N>
void add_linear_effect_torque(const Effect& effect, const EffectInput<S, N>& x,
                              JointVector<S, N>& tau) noexcept(N != Eigen::Dynamic) {
  const int columns = effect.columns();
  Eigen::Matrix<S, Effect::kColumns, 1> phi(columns), theta(columns);
  for (int j = 0; j < static_cast<int>(x.q.size()); ++j) {
    effect.coefficients(j, theta.data());
    if ((theta.array() == S(0)).all()) continue;
    Effect::basis(x, j, phi.data());
    S sum = S(0);
    for (int c = 0; c < columns; ++c)
      sum += phi[c] * theta[c];
    tau[j] += sum;
  }
}

}  // namespace tpf
