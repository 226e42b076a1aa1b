// `tpf demo`: the main job — the whole loop on the digital twin (simulate → nominal model →
// train → evaluate → report), with one progress line per stage.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "core/common/unoptimised_when_sanitized.hpp"
#include "offline/evaluate/evaluation_report.hpp"
#include "offline/measured_study/measured_report.hpp"
#include "offline/pipeline/demo_pipeline.hpp"
#include "offline/pipeline/tiago_report.hpp"
#include "offline/report/text_format.hpp"
#include "option_validators.hpp"
#include "tpf/common/error.hpp"

TPF_UNOPTIMISED_WHEN_SANITIZED_BEGIN

namespace tpf::cli {

void register_demo_command(CLI::App& app) {
  auto o = std::make_shared<offline::DemoOptions>();
  auto out = std::make_shared<std::string>("tpf-demo");
  auto verbose = std::make_shared<bool>(false);
  auto* cmd = app.add_subcommand(
      "demo",
      "Run the whole loop on the digital twin and on the measured Kinova Gen3 logs and write one "
      "report (the README's main job)");
  cmd->footer("Example: tpf demo --out demo   (then open demo/index.html)");
  cmd->add_option("--out", *out, "output folder for parameters, weights and the report")
      ->capture_default_str();
  cmd->add_option("--train-epochs", o->training_epochs,
                  "training budget: epochs per network (reproducible on any machine)")
      ->capture_default_str()
      ->check(at_least(1));
  cmd->add_option("--train-safety-seconds", o->training_safety_s,
                  "wall-clock safety net for the training [s] (0: none; the report says if it "
                  "triggered)")
      ->capture_default_str()
      ->check(non_negative());
  cmd->add_option("--train-duration", o->training_s, "simulated training log [s]")
      ->capture_default_str()
      ->check(positive(kMaxSimulatedSeconds));
  cmd->add_option("--test-duration", o->test_s, "simulated held-out excitation log [s]")
      ->capture_default_str()
      ->check(positive(kMaxSimulatedSeconds));
  cmd->add_option("--split-cutoff", o->split_cutoff_hz,
                  "cut-off of the zero-phase low/high split of the TCN target [Hz]")
      ->capture_default_str()
      ->check(split_cutoff_hz());
  cmd->add_option("--joint-hidden", o->joint_hidden,
                  "hidden channels of a per-joint network (16 or 32)")
      ->capture_default_str()
      ->check(one_of({offline::kPerJointHiddenSmall, offline::kPerJointHiddenLarge}));
  cmd->add_flag("!--all-joints", o->per_joint,
                "one network for all joints instead of one per joint (the default)");
  cmd->add_flag("!--no-twin", o->run_twin, "skip the digital twin (stages 1-5)");
  cmd->add_flag("!--no-measured", o->run_measured, "skip the Kinova Gen3 logs (stage 6, MEASURED)");
  cmd->add_flag("!--no-tiago", o->run_tiago, "skip the TIAGo log (stage 7, MEASURED)");
  cmd->add_option("--measured-epochs", o->measured.training_epochs,
                  "training budget of the measured compensator: epochs per network")
      ->capture_default_str()
      ->check(at_least(1));
  cmd->add_flag_callback(
      "--measured-every-input", [o] { o->measured.compensator_masked_inputs.clear(); },
      "the measured compensator sees every input (q and τ̂_fric,s too; by default it does not: "
      "the held-out files move outside the fitting files' range of q, and against the sensor "
      "τ̂_fric,s holds the rigid body's error)");
  cmd->add_flag("--verbose", *verbose,
                "print every stage's progress lines and the long summary (the report has both)");
  cmd->callback([o, out, verbose] {
    o->out = *out;
    if (!o->run_twin && !o->run_measured && !o->run_tiago)
      throw Error("tpf demo: --no-twin, --no-measured and --no-tiago leave nothing to run");
    std::vector<std::string> parts;
    if (o->run_twin) parts.push_back("the digital twin (SIMULATED)");
    if (o->run_measured) parts.push_back("the Kinova Gen3 logs (MEASURED)");
    if (o->run_tiago) parts.push_back("the TIAGo log (MEASURED)");
    std::printf("tpf demo: the whole loop on %s, output in %s\n",
                offline::joined(parts, " and on ").c_str(), out->c_str());
    // By default one line per stage ("[k/7] …"); --verbose: every line of every stage.
    const auto result = offline::run_demo(*o, [verbose](const std::string& line) {
      if (!*verbose && line.rfind('[', 0) != 0) return;
      std::printf("%s\n", line.c_str());
      std::fflush(stdout);
    });
    if (o->run_twin)
      std::printf("\nSIMULATED (digital twin)\n%s",
                  offline::evaluation_headline(result.evaluation, true).c_str());
    if (result.measured)
      std::printf(
          "\n%s",
          (*verbose ? offline::measured_headline(*result.measured, o->measured.target_reduction)
                    : offline::measured_brief(*result.measured, o->measured.target_reduction))
              .c_str());
    if (result.tiago)
      std::printf("\n%s\n%s\n", offline::kTiagoLabel,
                  offline::tiago_goal_sentence(*result.tiago, o->tiago).c_str());
    for (const auto& t : result.training.results)
      if (t.stopped_on_time) {
        std::printf(
            "\nWARNING: the training's wall-clock safety net (--train-safety-seconds) ended a "
            "network after %zu of %d epochs: these weights and numbers depend on this machine's "
            "speed\n",
            t.history.size(), o->training_epochs);
        break;
      }
    std::printf("\ntpf demo: done in %.0f s; report: %s\n", result.seconds,
                std::filesystem::absolute(result.index).string().c_str());
  });
}

}  // namespace tpf::cli

TPF_UNOPTIMISED_WHEN_SANITIZED_END
