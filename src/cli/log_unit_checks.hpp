// A log's units and dead channels checked against the robot file (offline/log/unit_check), as
// `tpf identify` prints them and writes them into the parameter file's fit ("log_checks").
#pragma once

#include <cmath>
#include <cstdio>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "offline/common/run_time_types.hpp"
#include "offline/log/unit_check.hpp"
#include "offline/samples/joint_samples.hpp"
#include "tpf/dynamics/rnea.hpp"

namespace tpf::cli {

/// The checks of `samples` with the robot file's `model` (its gravity torque at every sample).
inline offline::LogChecks check_log_units(const offline::ModelX& model,
                                          const offline::JointSamples& samples) {
  offline::UnitCheckInput in;
  in.t = samples.t;
  in.q = samples.q;
  in.dq = samples.dq;
  in.ddq = samples.ddq;
  in.effort = samples.effort;
  in.gravity.setConstant(samples.size(), samples.joints(),
                         std::numeric_limits<double>::quiet_NaN());
  offline::DataX data(model);
  Eigen::VectorXd q(model.joint_count());  // sized once, assigned per sample
  for (Eigen::Index r = 0; r < samples.size(); ++r) {
    q = samples.q.row(r).transpose();
    if (q.allFinite()) in.gravity.row(r) = compute_gravity(model, data, q).transpose();
  }
  in.gear_ratio = model.gear_ratio;
  in.torque_constant = model.torque_constant;
  in.effort_is_current = samples.units.unit == EffortUnit::Milliampere;
  in.lower = model.lower;
  in.upper = model.upper;
  for (int j = 0; j < model.joint_count(); ++j)
    in.prismatic.push_back(model.is_prismatic(j));
  return offline::check_log_units(in);
}

/// Notes a default printout shows of a list (--verbose: all).
inline constexpr std::size_t kNotesShown = 3;

/// Prints the first `shown` of `lines`, each after `prefix`, and how many more there are
/// ("  … 4 more (--verbose: all)").
inline void print_capped(const std::vector<std::string>& lines, const char* prefix,
                         std::size_t shown) {
  for (std::size_t k = 0; k < lines.size() && k < shown; ++k)
    std::printf("%s%s\n", prefix, lines[k].c_str());
  if (lines.size() > shown) std::printf("  … %zu more (--verbose: all)\n", lines.size() - shown);
}

/// Prints the checks ("log check: …" lines; "log checks: ok" when none; without `verbose` the
/// first kNotesShown notes and their count) and returns them, all, as the
/// fit's "log_checks": {"problems": [...], "notes": [...], "dead_joints": [1-based],
/// "rest_factor": [effort at rest / gravity torque, null: not checked]}.
inline nlohmann::json print_log_checks(const offline::LogChecks& checks, bool verbose = true) {
  std::printf("log checks against the robot file: %s\n",
              checks.problems.empty() ? "ok" : "PROBLEMS");
  for (const std::string& p : checks.problems)
    std::printf("  problem: %s\n", p.c_str());
  print_capped(checks.notes, "  note: ", verbose ? checks.notes.size() : kNotesShown);
  nlohmann::json rest = nlohmann::json::array();
  for (const double f : checks.rest_factor)
    rest.push_back(std::isfinite(f) ? nlohmann::json(f) : nlohmann::json(nullptr));
  return {{"problems", checks.problems},
          {"notes", checks.notes},
          {"dead_joints", checks.dead_joints},
          {"rest_factor", rest}};
}

}  // namespace tpf::cli
