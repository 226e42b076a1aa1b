// Folder pipeline/: `tpf demo`: every stage of the loop in order (simulate, identify, diagnose,
// train, calibrate, evaluate, then the measured study of measured_study/) and the one report.
//
// `tpf demo`: the whole loop on the digital twin, from simulation to one report.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "offline/compensator_training/train_compensator.hpp"
#include "offline/evaluate/evaluation.hpp"
#include "offline/measured_study/measured_pipeline.hpp"
#include "offline/pipeline/tiago_study.hpp"
#include "offline/report/html_report.hpp"

namespace tpf::offline {

struct DemoOptions {
  std::filesystem::path out = "tpf-demo";
  /// Training log: contact-free excitation with effects the nominal model does not declare.
  std::string training_scenario = "scenarios/excitation-undeclared.json";
  std::string test_scenario = "scenarios/excitation-undeclared.json";
  std::uint64_t training_seed = 1;
  std::uint64_t calibration_seed = 2;  ///< dead-band σ; never a test seed
  std::uint64_t test_seed = 3;         ///< held-out excitation
  std::uint64_t contacts_seed = 4;
  std::uint64_t teaching_seed = 5;
  /// 300 s keeps the test workflow's DemoTable within the CI budget; the compensator's goals
  /// (static −95 %, static-to-kinetic −75 %) are met from 600 s on (docs/evaluation.md).
  double training_s = 300.0;
  double calibration_s = 60.0;
  double test_s = 120.0;
  double contacts_s = 90.0;
  double teaching_s = 60.0;
  /// Training budget: epochs per network (early stopping may end sooner). An epoch budget, not a
  /// wall-clock one, so the same seeds give the same weights on every machine.
  int training_epochs = 100;
  /// Wall-clock safety net for the whole training [s] (0: none); the report says if it ended
  /// training, since the weights then depend on the machine's speed.
  double training_safety_s = 600.0;
  /// One network per joint (the default: measured better than one network for all joints on
  /// held-out twin data, docs/evaluation.md); false: one network for all joints.
  bool per_joint = true;
  int joint_hidden = kPerJointHiddenSmall;  ///< hidden channels of a per-joint network
  /// Cut-off of the trainer's zero-phase low/high split of the target [Hz].
  double split_cutoff_hz = 2.0;
  int threads = 2;
  bool run_twin = true;  ///< stages 1–5 (SIMULATED)
  /// The static-contacts and teaching logs (detection, force, teaching, closed loop); without
  /// them stage 5 scores Table I only.
  bool run_contacts = true;
  bool run_measured = true;  ///< stage 6: the Kinova Gen3 logs (MEASURED)
  MeasuredOptions measured;  ///< its out and threads are the demo's
  bool run_tiago = true;     ///< stage 7: the TIAGo log, held out by time (MEASURED)
  TiagoOptions tiago;        ///< its out and threads are the demo's
};

struct DemoResult {
  Evaluation evaluation;
  CompensatorTraining training;
  std::vector<std::string> findings;       ///< the diagnosis, in plain sentences
  Table diagnosis_summary;                 ///< the diagnosis at a glance (diagnosis_summary_table)
  std::vector<std::string> stages;         ///< the twin's logs, nominal model and training
  std::optional<MeasuredResult> measured;  ///< stage 6, when run
  std::optional<TiagoResult> tiago;        ///< stage 7, when run
  std::filesystem::path index;             ///< the report's entry page
  double seconds = 0.0;
};

/// The twin (SIMULATED): simulate (training, calibration and held-out logs, two at a time) →
/// identify → diagnose (the nominal model: declared + added effects) → train → evaluate; then the
/// Kinova Gen3 logs (MEASURED, run_measured, held out by file); then the TIAGo log (MEASURED,
/// run_tiago, held out by time); one report (out/index.html linking out/diagnose.html,
/// out/evaluate.html, out/measured.html and out/tiago.html; parameters, weights,
/// evaluation.json, measured.json and tiago.json beside it). `progress` gets one line per stage.
DemoResult run_demo(const DemoOptions& options,
                    const std::function<void(const std::string&)>& progress = {});

}  // namespace tpf::offline
