// A log's units and dead channels checked against the robot file (offline/log/unit_check), as
// `tpf identify` prints them and writes them into the parameter file's fit ("log_checks").
#pragma once

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "offline/samples/sample_unit_check.hpp"

namespace tpf::cli {

/// The checks of `samples` with the robot file's `model` (offline::check_sample_units), with
/// their gravity torque `gravity` where the caller has it (empty: computed).
inline offline::LogChecks check_log_units(const offline::ModelX& model,
                                          const offline::JointSamples& samples,
                                          const Eigen::MatrixXd& gravity = {}) {
  return offline::check_sample_units(model, samples, gravity);
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
