#include "offline/pipeline/demo_pipeline.hpp"

#include <atomic>
#include <chrono>
#include <cstdio>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

#include "offline/common/data_files.hpp"
#include "offline/evaluate/evaluation_report.hpp"
#include "offline/log/atomic_file.hpp"
#include "offline/pipeline/declared_model.hpp"
#include "offline/report/html_report.hpp"
#include "offline/report/text_format.hpp"
#include "offline/sim/simulate.hpp"
#include "offline/training/estimator_samples.hpp"

namespace tpf::offline {
namespace {

struct SimulationJob {
  std::string label;
  std::string scenario;
  std::uint64_t seed;
  double duration_s;
  Log log;
};

/// Runs the jobs on `threads` threads (each simulation is deterministic in its seed).
void simulate_all(std::vector<SimulationJob>& jobs, int threads,
                  const std::function<void(const std::string&)>& say) {
  std::atomic<std::size_t> next{0};
  std::mutex mutex;
  std::exception_ptr failure;
  const auto work = [&] {
    for (std::size_t k = next++; k < jobs.size(); k = next++) {
      SimulationJob& job = jobs[k];
      try {
        const Scenario scenario = load_scenario(data_file(job.scenario).string());
        job.log = simulate_to_log(scenario, job.seed, job.duration_s);
        job.log.source = job.label + " (simulated, " + job.scenario + ", seed " +
                         std::to_string(job.seed) + ", " + format_number(job.duration_s) + " s)";
        const std::lock_guard lock(mutex);
        say("simulate: " + job.log.source + " done");
      } catch (...) {
        const std::lock_guard lock(mutex);
        failure = std::current_exception();
      }
    }
  };
  std::vector<std::thread> pool;
  for (int i = 1; i < threads; ++i)
    pool.emplace_back(work);
  work();
  for (auto& t : pool)
    t.join();
  if (failure) std::rethrow_exception(failure);
}

void write_index(const std::filesystem::path& out, const DemoOptions& o, const DemoResult& r,
                 const std::vector<SimulationJob>& jobs) {
  HtmlReport page("tpf demo: the whole loop on the digital twin");
  page.mark_simulated();
  page.paragraph("simulate → nominal model → (diagnose) → train → evaluate, in " +
                 format_number(r.seconds, 3) + " s.");
  page.heading("Pages");
  page.list(
      {"evaluate.html — the three estimators side by side (Table I, dead bands, detection, "
       "force, teaching)",
       "diagnose: not run — `tpf diagnose` (branch loop) is not part of this build; the "
       "pipeline uses the declared model of the robot files as its nominal model"});
  page.paragraph("Open evaluate.html in this folder for the full report.");
  page.heading("Headline");
  page.preformatted(evaluation_headline(r.evaluation));
  page.heading("Stages");
  std::vector<std::string> stages;
  for (const SimulationJob& j : jobs)
    stages.push_back("log: " + j.log.source);
  stages.push_back(
      "nominal model: declared (robot file rigid body and armature + friction file Stribeck "
      "curve, mA) — written to nominal.params.json. Identification (`tpf identify`) is not in "
      "this build; the twin's undeclared effects (ripple, payload, thermal drift) are therefore "
      "left to the TCN.");
  std::string nets;
  for (const TcnTrainResult& t : r.training.results)
    nets += " best epoch " + std::to_string(t.best_epoch) + " of " +
            std::to_string(t.history.size()) + ";";
  stages.push_back(
      "train: " +
      std::string(o.per_joint ? "one network per joint" : "one network for all joints") +
      ", budget " + format_number(o.training_budget_s) +
      " s (the demo's short "
      "budget; `tpf train` defaults to 270 s), took " +
      format_number(r.training.seconds, 3) + " s;" + nets + " weights in tcn.json");
  page.list(stages);
  page.write(out / "index.html");
}

}  // namespace

DemoResult run_demo(const DemoOptions& o, const std::function<void(const std::string&)>& progress) {
  const auto start = std::chrono::steady_clock::now();
  const auto say = [&](const std::string& line) {
    if (progress) progress(line);
  };
  std::filesystem::create_directories(o.out);
  DemoResult result;

  // 1. Simulate.
  say("[1/5] simulate: training, calibration and held-out logs on " + std::to_string(o.threads) +
      " threads");
  std::vector<SimulationJob> jobs{
      {"training excitation", o.training_scenario, o.training_seed, o.training_s, {}},
      {"held-out excitation", o.test_scenario, o.test_seed, o.test_s, {}},
      {"static contacts", "scenarios/static-contacts.json", o.contacts_seed, o.contacts_s, {}},
      {"calibration excitation", o.test_scenario, o.calibration_seed, o.calibration_s, {}},
      {"teaching", "scenarios/teaching.json", o.teaching_seed, o.teaching_s, {}}};
  simulate_all(jobs, o.threads, say);
  const Log& training_log = jobs[0].log;

  // 2. Nominal model (identification is not in this build: the declared model).
  say("[2/5] nominal model: declared model of data/arm4.robot.json + data/arm4.friction.json "
      "(tpf identify not available in this build)");
  ArmEstimatorSetup setup;
  setup.nominal = declared_nominal_model(
      data_file("arm4.robot.json"), data_file("arm4.friction.json"), training_log.effort_prefix());
  save_nominal_model<kArmJoints>(o.out / "nominal.params.json", setup.nominal,
                                 "declared model (robot + friction files)");
  setup.pads = load_pads(data_file("arm4.pads.json"), setup.nominal.model);

  // 3. Diagnose: not in this build.
  say("[3/5] diagnose: skipped (tpf diagnose is not in this build)");

  // 4. Train.
  say("[4/5] train: estimator features on the training log, then the TCN (budget " +
      format_number(o.training_budget_s) + " s)");
  setup.parameters = arm_estimator_parameters(estimate_sensor_noise(training_log));
  const std::vector<EstimatorTrace> traces{
      trace_arm_estimator(setup, estimator_samples<kArmJoints, kArmPads>(training_log))};
  CompensatorTrainingOptions training;
  training.per_joint = o.per_joint;
  training.tcn.max_seconds = o.training_budget_s;
  training.tcn.threads = o.threads;
  training.tcn.seed = o.training_seed;
  int last_epoch = 0;
  result.training = train_compensator(
      traces, setup.nominal.effort_per_newton_metre, training, [&](const TcnTrainProgress& p) {
        if (p.epoch - last_epoch >= 5 || p.last) {
          last_epoch = p.epoch;
          char line[200];
          std::snprintf(
              line, sizeof line,
              "train: epoch %d, loss %.4g, held-out %.4g (best %.4g), %.0f s, ~%.0f s left",
              p.epoch, p.train_loss, p.validation_loss, p.best_validation_loss, p.elapsed_seconds,
              p.remaining_seconds);
          say(line);
        }
      });
  const auto weights = o.out / "tcn.json";
  setup.weight_files = write_compensator(result.training, weights);
  setup.layout = result.training.layout;

  // 5. Evaluate.
  say("[5/5] evaluate: held-out logs (seeds " + std::to_string(o.test_seed) + ", " +
      std::to_string(o.contacts_seed) + ", " + std::to_string(o.teaching_seed) + ")");
  EvaluationLogs logs;
  logs.calibration = &jobs[3].log;
  logs.excitation = {&jobs[1].log};
  logs.contacts = &jobs[2].log;
  logs.teaching = &jobs[4].log;
  setup.parameters = arm_estimator_parameters(estimate_sensor_noise(jobs[3].log));
  result.evaluation = evaluate(setup, logs, say);
  std::vector<std::string> notes{
      "nominal model: declared (robot + friction files); tpf identify/diagnose not in this build",
      "compensator: one network " + std::string(o.per_joint ? "per joint" : "for all joints") +
          ", trained " + format_number(result.training.seconds, 3) + " s on " + jobs[0].log.source};
  for (const SimulationJob& j : jobs)
    if (&j != &jobs[0]) notes.push_back("log: " + j.log.source);
  evaluation_report(result.evaluation, true, notes).write(o.out / "evaluate.html");
  AtomicFile json(o.out / "evaluation.json");
  json.write(evaluation_json(result.evaluation));
  json.commit();

  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  write_index(o.out, o, result, jobs);
  result.index = o.out / "index.html";
  return result;
}

}  // namespace tpf::offline
