#include "offline/identify/stribeck_fit.hpp"

#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "offline/identify/stribeck_curve_cost.hpp"

namespace tpf::offline {

namespace {

Eigen::VectorXd every_kth(const Eigen::VectorXd& v, Eigen::Index k) {
  if (k == 1) return v;
  return v(Eigen::seq(0, v.size() - 1, k));
}

// Bounds of x = [τ_c, τ_s, q̇_s, δ, b, α_c, α_v].
constexpr double kLower[7] = {0, 0, 1e-3, 0.3, 0, 0, 0};
constexpr double kUpper[7] = {1e12, 1e12, 2.0, 4.0, 1e12, 1e12, 1e12};

// The curve of x, and the names of its parameters that ended at a bound.
StribeckFit with_bounds_named(const double* x, bool fit_load, const double* lower,
                              const double* upper) {
  StribeckFit fit{{x[0], x[1], x[2], x[3], x[4], x[5], x[6]}, {}};
  static const char* kName[7] = {"τ_c", "τ_s", "q̇_s", "δ", "b", "α_c", "α_v"};
  for (int i = 0; i < 7; ++i) {
    if (!fit_load && i >= 5) continue;
    const double scale = std::max({std::abs(lower[i]), std::abs(x[i]), 1e-12});
    if (std::abs(x[i] - lower[i]) <= 1e-6 * scale)
      fit.at_bound.push_back(std::string(kName[i]) + " at its lower bound " +
                             std::to_string(lower[i]).substr(0, 5));
    else if (upper[i] < 1e12 && std::abs(x[i] - upper[i]) <= 1e-6 * scale)
      fit.at_bound.push_back(std::string(kName[i]) + " at its upper bound " +
                             std::to_string(upper[i]).substr(0, 5));
  }
  return fit;
}

// One local fit from x (in place); returns the final cost.
double solve_from(double* x, const Eigen::VectorXd& dq, const Eigen::VectorXd& abs_gravity,
                  const Eigen::VectorXd& target, bool fit_load, double cauchy_scale,
                  const double* lower, const double* upper) {
  ceres::Problem problem;
  problem.AddResidualBlock(new StribeckCurveCost(dq, abs_gravity, target, cauchy_scale), nullptr,
                           x);
  for (int i = 0; i < 7; ++i) {
    problem.SetParameterLowerBound(x, i, lower[i]);
    problem.SetParameterUpperBound(x, i, upper[i]);
  }
  if (!fit_load) {
    problem.SetManifold(x, new ceres::SubsetManifold(7, {5, 6}));
  }
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = 50;
  options.num_threads = 1;
  options.logging_type = ceres::SILENT;
  // Stop on the relative tolerances only: the absolute gradient tolerance would make the fit
  // depend on the unit of the torques (it is reached 10⁴–10⁵ times sooner in N·m than in mA).
  options.gradient_tolerance = 0.0;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  return summary.final_cost;
}

}  // namespace

StribeckFit fit_stribeck(const Eigen::VectorXd& dq, const Eigen::VectorXd& abs_gravity,
                         const Eigen::VectorXd& target, const JointStribeck& start, bool fit_load,
                         double cauchy_scale) {
  // Three starts, from a narrow dip to one as wide as the motion (friction that falls over the
  // whole range, which a linear fit shows as b < 0): the cost has a local minimum per width.
  const double dip[3][2] = {
      {std::clamp(start.stribeck_velocity, 2e-3, 1.0), 1.3}, {0.3, 1.5}, {1.5, 2.0}};
  // On more than 10 000 samples the starts race on every k-th (≈ 4 000) and the best one is
  // refined on all: the basin is found at a fraction of the cost.
  const Eigen::Index n = dq.size(), k = n > 10000 ? n / 4000 : 1;
  const Eigen::VectorXd coarse_dq = every_kth(dq, k), coarse_g = every_kth(abs_gravity, k),
                        coarse_target = every_kth(target, k);
  double x[7], best_cost = std::numeric_limits<double>::infinity();
  for (const auto& d : dip) {
    double trial[7] = {std::max(start.coulomb, 0.0),
                       std::max(start.coulomb, 0.0) * d[1],
                       d[0],
                       std::clamp(start.stribeck_exponent, 0.5, 3.0),
                       std::max(start.viscous, 0.0),
                       fit_load ? std::max(start.load_coulomb, 0.0) : 0.0,
                       fit_load ? std::max(start.load_viscous, 0.0) : 0.0};
    const double cost = solve_from(trial, coarse_dq, coarse_g, coarse_target, fit_load,
                                   cauchy_scale, kLower, kUpper);
    if (cost < best_cost) {
      best_cost = cost;
      std::copy(trial, trial + 7, x);
    }
  }
  if (k > 1) solve_from(x, dq, abs_gravity, target, fit_load, cauchy_scale, kLower, kUpper);
  return with_bounds_named(x, fit_load, kLower, kUpper);
}

StribeckFit refine_stribeck(const Eigen::VectorXd& dq, const Eigen::VectorXd& abs_gravity,
                            const Eigen::VectorXd& target, const JointStribeck& curve,
                            bool fit_load, double cauchy_scale) {
  double x[7] = {std::max(curve.coulomb, 0.0),
                 std::max(curve.static_friction, 0.0),
                 std::clamp(curve.stribeck_velocity, kLower[2], kUpper[2]),
                 std::clamp(curve.stribeck_exponent, kLower[3], kUpper[3]),
                 std::max(curve.viscous, 0.0),
                 fit_load ? std::max(curve.load_coulomb, 0.0) : 0.0,
                 fit_load ? std::max(curve.load_viscous, 0.0) : 0.0};
  solve_from(x, dq, abs_gravity, target, fit_load, cauchy_scale, kLower, kUpper);
  return with_bounds_named(x, fit_load, kLower, kUpper);
}

}  // namespace tpf::offline
