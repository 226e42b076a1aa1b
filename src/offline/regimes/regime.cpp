#include "offline/regimes/regime.hpp"

#include <algorithm>
#include <cmath>

#include "offline/signal/segments.hpp"
#include "tpf/common/error.hpp"

namespace tpf::offline {

std::string_view regime_name(Regime regime) {
  switch (regime) {
    case Regime::Static:
      return "static";
    case Regime::StaticToKinetic:
      return "static-to-kinetic";
    case Regime::Moving:
      return "moving";
    case Regime::Invalid:
      return "invalid";
  }
  return "invalid";
}

std::vector<Regime> label_regimes(const Eigen::VectorXd& t, const Eigen::VectorXd& dq,
                                  const RegimeOptions& options,
                                  const Eigen::VectorXd* residual_nominal,
                                  const Eigen::VectorXd* residual_compensated,
                                  double meet_tolerance) {
  const Eigen::Index n = t.size();
  const auto check = [&](const Eigen::VectorXd* v, const char* name) {
    if (v != nullptr && v->size() != n)
      throw Error(std::string("label_regimes: ") + name + " has " + std::to_string(v->size()) +
                  " samples, t has " + std::to_string(n));
  };
  check(&dq, "dq");
  check(residual_nominal, "residual_nominal");
  check(residual_compensated, "residual_compensated");
  const bool use_residuals = residual_nominal != nullptr && residual_compensated != nullptr;
  const double window = use_residuals
                            ? options.max_transition_s
                            : std::min(options.fallback_transition_s, options.max_transition_s);
  const double max_step = options.gap_factor * median_step(t);

  std::vector<Regime> labels(static_cast<std::size_t>(n), Regime::Invalid);
  const auto label = [&](Eigen::Index k) -> Regime& { return labels[static_cast<std::size_t>(k)]; };
  const auto valid = [&](Eigen::Index k) { return std::isfinite(t[k]) && std::isfinite(dq[k]); };
  const auto is_static = [&](Eigen::Index k) { return std::abs(dq[k]) < options.static_velocity; };
  const auto joined = [&](Eigen::Index k) {  // sample k follows k−1 without gap or NaN
    return k > 0 && valid(k - 1) && valid(k) && !(t[k] - t[k - 1] > max_step);
  };
  const auto difference = [&](Eigen::Index k) {
    return (*residual_nominal)[k] - (*residual_compensated)[k];
  };

  Eigen::Index k = 0;
  while (k < n) {
    if (!valid(k)) {
      ++k;
      continue;
    }
    if (is_static(k)) {
      label(k++) = Regime::Static;
      continue;
    }
    if (!(joined(k) && label(k - 1) == Regime::Static)) {
      label(k++) = Regime::Moving;
      continue;
    }
    // Upward crossing at k0: the transition window.
    const Eigen::Index k0 = k;
    const double d0 = use_residuals ? difference(k0) : 0.0;
    label(k++) = Regime::StaticToKinetic;
    while (k < n && joined(k) && !is_static(k) && t[k] - t[k0] < window) {
      if (use_residuals) {
        const double d = difference(k);
        if (std::abs(d) <= meet_tolerance || (d0 > 0 && d < 0) || (d0 < 0 && d > 0)) break;
      }
      label(k++) = Regime::StaticToKinetic;
    }
  }
  return labels;
}

}  // namespace tpf::offline
