#include "offline/pipeline/demo_pipeline.hpp"

#include <atomic>
#include <chrono>
#include <cstdio>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

#include "core/common/atomic_file.hpp"
#include "core/common/unoptimised_when_sanitized.hpp"
#include "offline/common/data_files.hpp"
#include "offline/diagnose/diagnose.hpp"
#include "offline/diagnose/diagnosis_report.hpp"
#include "offline/diagnose/diagnosis_summary.hpp"
#include "offline/evaluate/evaluation_report.hpp"
#include "offline/identify/identify.hpp"
#include "offline/measured_study/measured_report.hpp"
#include "offline/pipeline/demo_index.hpp"
#include "offline/pipeline/tiago_report.hpp"
#include "offline/replay/estimator_samples.hpp"
#include "offline/report/html_report.hpp"
#include "offline/report/text_format.hpp"
#include "offline/sim/simulate.hpp"
#include "tpf/estimation/estimator_parameter_file.hpp"
#include "tpf/model/load_robot.hpp"

TPF_UNOPTIMISED_WHEN_SANITIZED_BEGIN

namespace tpf::offline {

/// The demo runs the twin of the project's 4-joint arm (data/arm4.*).
constexpr int kDemoJoints = 4;
namespace {

struct SimulationJob {
  std::string label;
  std::string scenario;
  std::uint64_t seed;
  double duration_s;
  Log log;
};

/// Runs the jobs on `threads` threads (each simulation is deterministic in its seed). Every log is
/// recorded on the same arm: each job's scenario keeps its script, drive and sensors but takes the
/// arm's physical effects (payload, ripple, load friction, …).
void simulate_all(std::vector<SimulationJob>& jobs, const EffectsConfig& arm, int threads,
                  const std::function<void(const std::string&)>& say) {
  std::atomic<std::size_t> next{0};
  std::mutex mutex;
  std::exception_ptr failure;
  const auto work = [&] {
    for (std::size_t k = next++; k < jobs.size(); k = next++) {
      SimulationJob& job = jobs[k];
      try {
        Scenario scenario = load_scenario(data_file(job.scenario).string());
        scenario.effects = arm;
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

/// " best epoch b of n;" per network, and a warning when the wall-clock safety net ended one.
std::string training_summary(const CompensatorTraining& training) {
  std::string text;
  for (const TcnTrainResult& t : training.results) {
    text += " best epoch " + std::to_string(t.best_epoch) + " of " +
            std::to_string(t.history.size()) + (t.stopped_early ? " (early stop);" : ";");
    if (t.stopped_on_time)
      text += " STOPPED BY THE WALL-CLOCK SAFETY NET: these weights depend on the machine's speed;";
  }
  return text;
}

/// Stages 1–5: the loop on the digital twin (SIMULATED).
void run_twin(const DemoOptions& o, DemoResult& result, std::vector<SimulationJob>& jobs,
              const std::function<void(const std::string&)>& say) {
  // 1. Simulate.
  say("[1/7] simulate: training, calibration and held-out logs on " + std::to_string(o.threads) +
      " threads");
  jobs = {{"training excitation", o.training_scenario, o.training_seed, o.training_s, {}},
          {"held-out excitation", o.test_scenario, o.test_seed, o.test_s, {}},
          {"calibration excitation", o.test_scenario, o.calibration_seed, o.calibration_s, {}}};
  if (o.run_contacts) {
    jobs.push_back(
        {"static contacts", "scenarios/static-contacts.json", o.contacts_seed, o.contacts_s, {}});
    jobs.push_back({"teaching", "scenarios/teaching.json", o.teaching_seed, o.teaching_s, {}});
  }
  // The arm is the training scenario's: the held-out, contact and teaching logs come from the same
  // plant the model was identified on (its payload, ripple, … included).
  const EffectsConfig arm = load_scenario(data_file(o.training_scenario).string()).effects;
  simulate_all(jobs, arm, o.threads, say);
  const Log& training_log = jobs[0].log;

  // 2. Identify the declared model on the training log.
  say("[2/7] identify: declared model (base parameters, armature, Stribeck + load friction) on "
      "the training log");
  const ModelX model = load_robot<double, Eigen::Dynamic>(data_file("arm4.robot.json"));
  DiagnoseOptions diagnose_options;
  diagnose_options.progress = say;
  IdentifyOptions identify_options;
  identify_options.samples = diagnose_options.samples;
  identify_options.progress = say;
  // The samples and their regressors once, for identify and then diagnose.
  IdentificationSetup prepared = prepare_diagnosis(training_log, model, diagnose_options.samples);
  const BaseParameters base = prepared.base;
  const auto regressors = prepared.regressors;
  const auto abs_gravity = prepared.abs_gravity;
  const auto gravity = prepared.gravity;
  Identification identified = identify(training_log, model, std::move(prepared), identify_options);
  save_nominal_model(o.out / "identified.params.json", identified.nominal, training_log.source);

  // 3. Diagnose from identify's fit: name and add what the declared model misses; the result is
  // the nominal model.
  say("[3/7] diagnose: candidate effects on the training log's held-out blocks");
  const Diagnosis diagnosis = diagnose(
      training_log, model, {std::move(identified.samples), base, regressors, abs_gravity, gravity},
      identified, diagnose_options);
  for (const std::string& f : diagnosis.findings)
    say("diagnose: " + f);
  save_nominal_model(o.out / "nominal.params.json", diagnosis.nominal, training_log.source);
  write_diagnosis_report(diagnosis, o.out / "diagnose.html", diagnose_options);
  AtomicFile diagnosis_file(o.out / "diagnosis.json");
  diagnosis_file.write(diagnosis_json(diagnosis));
  diagnosis_file.commit();
  result.findings = diagnosis.findings;
  result.diagnosis_summary = diagnosis_summary_table(diagnosis, diagnose_options);
  ReplaySetup setup;
  setup.nominal = diagnosis.nominal;
  setup.pads = load_pads(data_file("arm4.pads.json"), setup.nominal.model);
  const int pads = static_cast<int>(setup.pads.size());

  // 4. Train.
  say("[4/7] train: estimator features on the training log, then the TCN (" +
      std::to_string(o.training_epochs) + " epochs per network at most)");
  setup.parameters = estimator_parameters_from_noise(
      estimate_sensor_noise(training_log, setup.nominal.model.torque_constant));
  const std::vector<EstimatorTrace> traces{
      replay_estimator(setup, estimator_samples(training_log, setup.nominal.model, pads))};
  CompensatorTrainingOptions training;
  training.per_joint = o.per_joint;
  training.joint_hidden = o.joint_hidden;
  training.tcn.max_seconds = o.training_safety_s;
  training.tcn.max_epochs = o.training_epochs;
  training.tcn.split_cutoff_hz = o.split_cutoff_hz;
  training.tcn.threads = o.threads;
  training.tcn.seed = o.training_seed;
  int last_epoch = 0;
  result.training = train_compensator(traces, training, [&](const TcnTrainProgress& p) {
    if (p.epoch - last_epoch >= 5 || p.last) {
      last_epoch = p.epoch;
      char line[200];
      std::snprintf(line, sizeof line,
                    "train: epoch %d, loss %.4g, held-out %.4g (best %.4g), %.0f s, ~%.0f s left",
                    p.epoch, p.train_loss, p.validation_loss, p.best_validation_loss,
                    p.elapsed_seconds, p.remaining_seconds);
      say(line);
    }
  });
  const auto weights = o.out / "tcn.json";
  write_compensator(result.training, weights);
  setup.weights = find_compensator_weights(weights, kDemoJoints);

  // 5. Evaluate.
  say("[5/7] evaluate: held-out logs (seeds " + std::to_string(o.test_seed) + ", " +
      std::to_string(o.contacts_seed) + ", " + std::to_string(o.teaching_seed) + ")");
  EvaluationLogs logs;
  logs.calibration = &jobs[2].log;
  logs.excitation = {&jobs[1].log};
  Scenario teaching = load_scenario(data_file("scenarios/teaching.json").string());
  teaching.effects = arm;  // the closed loop runs on the same arm
  if (o.run_contacts) {
    logs.contacts = &jobs[3].log;
    logs.teaching = &jobs[4].log;
    logs.teaching_scenario = &teaching;
    logs.teaching_seed = o.teaching_seed;
    logs.teaching_duration_s = o.teaching_s;
  }
  setup.parameters = estimator_parameters_from_noise(
      estimate_sensor_noise(jobs[2].log, setup.nominal.model.torque_constant));
  result.evaluation = evaluate(setup, logs, say);
  // The run-time loop's estimator parameters as calibrated here (tpf_arm_loop --estimator).
  save_estimator_parameters(o.out / "arm4.estimator.json", setup.parameters,
                            jobs[2].log.source + " (SIMULATED log)");
  std::vector<std::string> notes{
      "nominal model: identified and diagnosed on the training log (nominal.params.json)",
      "arm: every log is simulated on one arm, with the physical effects of " +
          o.training_scenario + " (the contact and teaching scripts keep their own motion)",
      "compensator: one network " + std::string(o.per_joint ? "per joint" : "for all joints") +
          ", trained " + format_number(result.training.seconds, 3) + " s on " + jobs[0].log.source +
          ";" + training_summary(result.training)};
  for (const SimulationJob& j : jobs)
    if (&j != &jobs[0]) notes.push_back("log: " + j.log.source);
  for (const SimulationJob& j : jobs)
    result.stages.push_back("log: " + j.log.source);
  result.stages.push_back(
      "nominal model: identify then diagnose on the training log (identified.params.json, "
      "nominal.params.json = identified + the effects diagnosis added)");
  result.stages.push_back(
      "train: " +
      std::string(o.per_joint ? "one network per joint" : "one network for all joints") +
      ", budget " + std::to_string(o.training_epochs) +
      " epochs per network (reproducible: the same seed gives the same weights on any "
      "machine), took " +
      format_number(result.training.seconds, 3) + " s;" + training_summary(result.training) +
      " weights in tcn.json or tcn.joint<j>.json");
  evaluation_report(result.evaluation, true, notes).write(o.out / "evaluate.html");
  AtomicFile json(o.out / "evaluation.json");
  json.write(evaluation_json(result.evaluation));
  json.commit();
}

}  // namespace

DemoResult run_demo(const DemoOptions& o, const std::function<void(const std::string&)>& progress) {
  const auto start = std::chrono::steady_clock::now();
  const auto say = [&](const std::string& line) {
    if (progress) progress(line);
  };
  std::filesystem::create_directories(o.out);
  DemoResult result;
  std::vector<SimulationJob> jobs;
  if (o.run_twin) run_twin(o, result, jobs, say);
  if (o.run_measured) {
    say("[6/7] measured: the Kinova Gen3 logs, held out by file (" + std::string(kMeasuredLabel) +
        ")");
    MeasuredOptions measured = o.measured;
    measured.out = o.out;
    measured.threads = o.threads;
    result.measured = run_measured(measured, say);
    write_measured_report(*result.measured, measured, o.out);
  }
  if (o.run_tiago) {
    say("[7/7] measured: the TIAGo log, held out by time (" + std::string(kTiagoLabel) + ")");
    TiagoOptions tiago = o.tiago;
    tiago.out = o.out;
    tiago.threads = o.threads;
    result.tiago = run_tiago_study(tiago, say);
    write_tiago_report(*result.tiago, tiago, o.out);
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  write_demo_index(o.out, o, result);
  result.index = o.out / "index.html";
  return result;
}

}  // namespace tpf::offline

TPF_UNOPTIMISED_WHEN_SANITIZED_END
