// The run-time torque of an effect that is linear in its parameters: per joint, its basis
// functions (the regressor columns diagnose fits) times its coefficients. One definition of the
// columns serves the fit and the run time, so the two agree by construction.
#pragma once

#include <algorithm>
#include <array>

#include "tpf/effects/effect_input.hpp"

namespace tpf {

/// τ_j += Σ_c φ_c(x)·θ_jc for every joint j, with φ = Effect::basis(x, j, ·) and θ_j =
/// effect.coefficients(j, ·) (Effect::kColumns of each). A joint whose θ_j is all zero (the effect
/// not added there) is skipped: its basis is not evaluated. Allocation-free.
template <typename Effect, typename S, int N>
void add_linear_effect_torque(const Effect& effect, const EffectInput<S, N>& x,
                              JointVector<S, N>& tau) noexcept {
  std::array<S, Effect::kColumns> phi{}, theta{};
  for (int j = 0; j < N; ++j) {
    effect.coefficients(j, theta.data());
    if (std::all_of(theta.begin(), theta.end(), [](S c) { return c == S(0); })) continue;
    Effect::basis(x, j, phi.data());
    S sum = S(0);
    for (int c = 0; c < Effect::kColumns; ++c)
      sum += phi[c] * theta[c];
    tau[j] += sum;
  }
}

}  // namespace tpf
