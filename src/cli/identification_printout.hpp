// What `tpf identify` prints and writes once the model is identified: the held-out table, the
// consistency check and the parameter file (also `tpf diagnose --identify-out`).
#pragma once

#include <chrono>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>

#include "log_unit_checks.hpp"
#include "offline/identify/identify.hpp"
#include "offline/log/log.hpp"

namespace tpf::cli {

/// Prints which strength of the inertia prior identify chose and why (a table of the strengths
/// tried, with `verbose`), and keeps them in `fit["inertia_prior"]`.
inline void print_inertia_prior_choice(const offline::Identification::InertiaPrior& prior,
                                       nlohmann::json& fit, bool verbose) {
  std::printf(
      "inertia prior: M(q)'s smallest eigenvalue without it %.4g kg·m² (judged fit), %.4g "
      "(written fit); the rigid body pulled toward the robot file's inertias with strength "
      "%.3g (judged) and %.3g (written): %s\n",
      prior.judged_min_eigenvalue, prior.written_min_eigenvalue, prior.judged_strength,
      prior.written_strength, prior.choice.c_str());
  if (verbose)
    std::printf(
        "  strength   held-out error (in σ)   min eigenvalue of M(q) [kg·m²] against the floor "
        "%.4g (a tenth of the robot file's own)\n",
        prior.floor);
  else
    std::printf("  (--verbose: the %zu strengths tried)\n", prior.candidates.size());
  nlohmann::json candidates = nlohmann::json::array();
  for (const auto& c : prior.candidates) {
    if (verbose)
      std::printf("  %8.3g   %21.4f   %+14.4g %s%s\n", c.strength, c.heldout_error,
                  c.min_eigenvalue, c.positive_definite ? "above: positive definite" : "below",
                  c.strength == prior.judged_strength ? "  <- chosen" : "");
    candidates.push_back(
        {{"strength", c.strength},
         {"heldout_error", std::isfinite(c.heldout_error) ? nlohmann::json(c.heldout_error)
                                                          : nlohmann::json(nullptr)},
         {"min_mass_eigenvalue", c.min_eigenvalue},
         {"positive_definite", c.positive_definite}});
  }
  fit["inertia_prior"] = {{"judged_strength", prior.judged_strength},
                          {"written_strength", prior.written_strength},
                          {"judged_min_mass_eigenvalue_without", prior.judged_min_eigenvalue},
                          {"written_min_mass_eigenvalue_without", prior.written_min_eigenvalue},
                          {"floor", prior.floor},
                          {"choice", prior.choice},
                          {"candidates", candidates}};
}

/// Prints the identification of `log` (held-out RMSE per joint and regime in the log's unit,
/// consistency, friction notes) and writes its model to `out` (tpf-params), with the wall time
/// since `start`. `log_checks` (the log against the robot file, check_log_units) are printed
/// after the consistency check and written as the fit's "log_checks". Without `verbose` the notes
/// and the inertia prior's table are cut to their first lines; the file's fit keeps them all.
inline void print_and_save_identification(const offline::Log& log,
                                          const offline::Identification& id,
                                          const offline::SampleOptions& sample_options,
                                          const std::string& out,
                                          std::chrono::steady_clock::time_point start,
                                          const offline::LogChecks& log_checks,
                                          bool verbose = true) {
  using offline::Regime;
  const auto& s = id.samples;
  std::printf("%s%s: %ld samples (%s), effort in %s\n", s.simulated ? "SIMULATED log " : "log ",
              log.source.c_str(), static_cast<long>(s.size()),
              offline::skipped_samples_text(s).c_str(), s.units.name());
  std::printf("held-out residual RMSE [%s]     static  static-to-kinetic   moving      all\n",
              s.units.name());
  nlohmann::json fit;
  for (int j = 0; j < s.joints(); ++j) {
    const auto& h = id.heldout[j];
    // Fitted in N·m; printed in the log's unit (mA for a log of currents).
    const auto in_log_unit = [&](double tau) { return s.units.to_effort(j, tau); };
    std::printf("  joint %d  %28.3f %18.3f %8.3f %8.3f\n", j + 1,
                in_log_unit(h[Regime::Static].rmse), in_log_unit(h[Regime::StaticToKinetic].rmse),
                in_log_unit(h[Regime::Moving].rmse), in_log_unit(h.valid.rmse));
    fit["heldout_rmse"].push_back({{"static", h[Regime::Static].rmse},
                                   {"static-to-kinetic", h[Regime::StaticToKinetic].rmse},
                                   {"moving", h[Regime::Moving].rmse},
                                   {"all", h.valid.rmse}});
  }
  const std::string held_out_note = nothing_held_out_note(s, sample_options);
  if (!held_out_note.empty()) std::printf("note: %s\n", held_out_note.c_str());
  std::printf("consistency: %s (min eigenvalue of M(q) %.4g kg·m²)\n",
              id.consistency.consistent() ? "ok" : "PROBLEMS", id.consistency.min_mass_eigenvalue);
  for (const auto& p : id.consistency.problems)
    std::printf("  problem: %s\n", p.c_str());
  fit["log_checks"] = print_log_checks(log_checks, verbose);
  const auto& prior = id.inertia_prior;
  if (prior.asked && !(prior.floor > 0)) {
    std::printf(
        "inertia prior: not applied: the robot file's own M(q) is not positive definite "
        "(smallest eigenvalue %.4g kg·m² at the check's poses: a joint with no link inertia of "
        "its own or beyond it and no rotor_inertia?), so it sets no floor to lift the fit's to\n",
        10 * prior.floor);
    fit["inertia_prior"] = {{"applied", false},
                            {"robot_file_min_mass_eigenvalue", 10 * prior.floor}};
  } else if (prior.asked && prior.judged_strength == 0 && prior.written_strength == 0) {
    std::printf(
        "inertia prior: not needed (M(q)'s smallest eigenvalue is at least a tenth of "
        "the robot file's own without it)\n");
  } else if (prior.asked) {
    print_inertia_prior_choice(prior, fit, verbose);
  }
  print_capped(id.friction_notes, "  friction: ", verbose ? id.friction_notes.size() : kNotesShown);
  fit["friction_notes"] = id.friction_notes;
  if (!held_out_note.empty()) fit["heldout_note"] = held_out_note;
  fit["consistent"] = id.consistency.consistent();
  fit["problems"] = id.consistency.problems;
  fit["simulated"] = s.simulated;
  tpf::save_nominal_model(out, id.nominal, log.source, fit.dump());
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("wrote %s (%.1f s)%s\n", out.c_str(), wall,
              id.refitted ? ": the model refitted on every sample, the held-out ones included "
                            "(the held-out figures above are of its fit without them)"
                          : "");
}

}  // namespace tpf::cli
