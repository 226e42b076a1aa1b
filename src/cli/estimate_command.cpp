// `tpf estimate`: the run-time estimator replayed over any recorded log — the est_* columns the arm
// loop writes, the contact episodes it found, and a plot of τ̂_ext against time.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "commands.hpp"
#include "compensator_gate_printout.hpp"
#include "core/common/atomic_file.hpp"
#include "model_file_options.hpp"
#include "core/common/unoptimised_when_sanitized.hpp"
#include "offline/log/log_writer.hpp"
#include "offline/log/read_log.hpp"
#include "offline/replay/contact_episodes.hpp"
#include "offline/replay/estimate_columns.hpp"
#include "offline/report/estimate_page.hpp"
#include "offline/report/text_table.hpp"
#include "option_validators.hpp"
#include "output_collisions.hpp"
#include "read_command_logs.hpp"
#include "robot_joint_count.hpp"
#include "tpf/estimation/estimator_parameter_file.hpp"
#include "tpf/estimation/estimator_status.hpp"

TPF_UNOPTIMISED_WHEN_SANITIZED_BEGIN

namespace {

struct EstimateCommandOptions {
  tpf::cli::ModelFiles model;
  std::string log, estimator, weights, out, report, json;
  double merge_gap_s = 0.1;
  bool verbose = false;
};

/// Episodes the default printout lists (--verbose: all).
constexpr std::size_t kEpisodesShown = 15;

/// The page beside the output log: "run.est.csv" → "run.est.html" (".csv.gz" likewise).
std::string default_report_path(const std::string& out) {
  std::filesystem::path p(out);
  if (p.extension() == ".gz") p.replace_extension();
  p.replace_extension(".html");
  return p.string();
}

/// What one replay found, for the printout and the JSON.
struct EstimateSummary {
  tpf::offline::Log log;  ///< the output log: the input with its est_* columns
  int joints = 0;
  bool simulated = false;
  std::vector<tpf::offline::ContactEpisode> episodes;
  std::array<long, tpf::kEstimatorStatusBits> status_cycles{};  ///< cycles with each bit set
  long contact_cycles = 0;
};

EstimateSummary replay_log(const EstimateCommandOptions& o, const tpf::offline::ReplaySetup& setup,
                           const tpf::offline::Log& log) {
  using namespace tpf::offline;
  EstimateSummary s;
  s.joints = setup.nominal.model.joint_count();
  const auto source = log.meta.get("source");
  s.simulated = source && source->find("simulated") != std::string::npos;
  const auto samples =
      estimator_samples(log, setup.nominal.model, static_cast<int>(setup.pads.size()));
  auto estimator = make_replay_estimator(setup);
  const Eigen::MatrixXd est = estimate_columns(*estimator, samples);
  s.log = with_estimate_columns(log, est);
  s.log.meta.set("estimated_by", "tpf estimate, nominal model " + o.model.params + ", estimator " +
                                     o.estimator + ", compensator " +
                                     (o.weights.empty() ? "none" : o.weights));
  const Eigen::VectorXd contact = est.col(s.joints);
  for (Eigen::Index r = 0; r < est.rows(); ++r) {
    const auto status = static_cast<std::uint32_t>(est(r, est.cols() - 1));
    for (int b = 0; b < tpf::kEstimatorStatusBits; ++b)
      s.status_cycles[static_cast<std::size_t>(b)] += (status >> b) & 1u;
    s.contact_cycles += contact[r] == 1.0;
  }
  s.episodes = contact_episodes(log.col("t"), contact, est.leftCols(s.joints),
                                setup.parameters.static_dead_band, o.merge_gap_s);
  return s;
}

nlohmann::json summary_json(const EstimateSummary& s, const EstimateCommandOptions& o) {
  nlohmann::json j;
  j["log"] = o.log;
  j["out"] = o.out;
  j["data"] = s.simulated ? "SIMULATED" : "MEASURED";
  j["rows"] = s.log.rows();
  j["contact_cycles"] = s.contact_cycles;
  nlohmann::json status = nlohmann::json::object();
  for (int b = 0; b < tpf::kEstimatorStatusBits; ++b)
    status[tpf::estimator_status_name(b)] = s.status_cycles[static_cast<std::size_t>(b)];
  j["status_cycles"] = status;
  j["episodes"] = nlohmann::json::array();
  for (const auto& e : s.episodes) {
    std::vector<int> joints;
    for (int q : e.joints)
      joints.push_back(q + 1);
    j["episodes"].push_back(
        {{"start_s", e.start_s},
         {"end_s", e.end_s},
         {"joints", joints},
         {"peak_abs_tau_ext_nm",
          std::vector<double>(e.peak_abs_torque.begin(), e.peak_abs_torque.end())}});
  }
  return j;
}

void print_estimate_summary(const EstimateSummary& s, const EstimateCommandOptions& o) {
  using namespace tpf::offline;
  const double rows = static_cast<double>(std::max<Eigen::Index>(s.log.rows(), 1));
  std::printf("estimate: %zu contact episodes, in contact %.1f %% of the cycles\n",
              s.episodes.size(), 100.0 * static_cast<double>(s.contact_cycles) / rows);
  for (int b = 0; b < tpf::kEstimatorStatusBits; ++b)
    if (const long n = s.status_cycles[static_cast<std::size_t>(b)]; n > 0 || o.verbose)
      std::printf("  status %-30s %8ld cycles (%.1f %%)\n", tpf::estimator_status_name(b), n,
                  100.0 * static_cast<double>(n) / rows);
  if (s.episodes.empty()) return;
  const std::size_t shown =
      o.verbose ? s.episodes.size() : std::min(s.episodes.size(), kEpisodesShown);
  Table table = episode_table(
      std::vector<ContactEpisode>(s.episodes.begin(),
                                  s.episodes.begin() + static_cast<std::ptrdiff_t>(shown)),
      s.joints);
  std::printf("%s", table_text(table).c_str());
  if (shown < s.episodes.size())
    std::printf("  … %zu more (--verbose or --json: all)\n", s.episodes.size() - shown);
}

void write_estimate_page(const EstimateSummary& s, const EstimateCommandOptions& o,
                         const std::string& report) {
  using namespace tpf::offline;
  EstimatePageData page;
  page.log = o.log;
  page.simulated = s.simulated;
  const auto source = s.log.meta.get("source");
  const auto licence = s.log.meta.get("license");
  page.provenance = (source ? *source : std::string("source not recorded")) +
                    (licence ? "; licence " + *licence : std::string());
  page.t = s.log.col("t");
  page.tau_ext.resize(s.log.rows(), s.joints);
  for (int j = 0; j < s.joints; ++j)
    page.tau_ext.col(j) = s.log.col(indexed_name("est_tau_ext", j + 1));
  page.contact = s.log.col("est_contact");
  if (s.log.has("gt_contact")) page.truth_contact = s.log.col("gt_contact");
  page.episodes = s.episodes;
  page.notes = {
      "log: " + o.log, "nominal model: " + o.model.params, "estimator parameters: " + o.estimator,
      "compensator: " + (o.weights.empty() ? std::string("none") : o.weights), "written: " + o.out};
  estimate_page(page).write(report);
}

void run_estimate(const EstimateCommandOptions& o, const std::string& report) {
  using namespace tpf::offline;
  ReplaySetup setup = tpf::cli::load_model_setup(o.model, o.weights);
  const int joints = setup.nominal.model.joint_count();
  setup.parameters = tpf::load_estimator_parameters(o.estimator, joints);
  const Log log = tpf::cli::read_replayed_log(o.log, false);
  tpf::cli::require_log_joint_count(log.joint_count(), o.log, o.model.robot);
  const EstimateSummary s = replay_log(o, setup, log);
  std::printf("estimate: %s (%s), %lld rows, %.1f s; %d joints, %s, %s\n", o.log.c_str(),
              s.simulated ? "SIMULATED" : "MEASURED", static_cast<long long>(log.rows()),
              log.rows() > 1 ? log.col("t")[log.rows() - 1] - log.col("t")[0] : 0.0, joints,
              tpf::cli::describe_pads(
                  setup.pads.size(),
                  tpf::cli::pad_layout_file(o.model, tpf::load_robot_description(o.model.robot)))
                  .c_str(),
              describe(setup.weights).c_str());
  tpf::cli::print_compensated_joints("estimate", setup.weights, joints,
                                     setup.parameters.compensator_min_held_out_gain);
  print_estimate_summary(s, o);
  // Every output is complete or absent: written only once the replay has succeeded.
  write_log(o.out, s.log);
  write_estimate_page(s, o, report);
  if (!o.json.empty()) tpf::write_file_atomically(o.json, summary_json(s, o).dump(1) + "\n");
  std::printf("estimate: wrote %s, %s%s%s\n", o.out.c_str(), report.c_str(),
              o.json.empty() ? "" : ", ", o.json.c_str());
}

}  // namespace

namespace tpf::cli {

void register_estimate_command(CLI::App& app) {
  auto o = std::make_shared<EstimateCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "estimate",
      "Replay the run-time estimator over a recorded log: est_* columns, contact episodes, plot");
  cmd->footer(
      "Runs the arm loop's estimator (same code, held-out compensator gate included) over the log "
      "and writes it back with the est_* columns tpf_arm_loop writes: est_tau_ext<j> [N*m], "
      "est_contact, est_pad, est_fx/fy/fz [N], est_status (docs/log-format.md). Prints the "
      "contact episodes (start, end, joints, peak |tau_ext|) and writes a page plotting tau_ext "
      "against time with the contacts marked.\n"
      "Example: tpf estimate --log push.csv --params arm4.params.json --estimator "
      "arm4.estimator.json --weights arm4.tcn.json --out push.est.csv");
  cmd->add_option("--log", o->log, "Recorded log (tpf CSV, .csv or .csv.gz, effort i<j> or tau<j>)")
      ->required()
      ->check(input_file());
  add_model_file_options(cmd, o->model, "Nominal model (tpf-params file, tpf identify)");
  cmd->add_option("--estimator", o->estimator,
                  "Estimator parameter file (tpf calibrate), e.g. data/arm4.estimator.json")
      ->required()
      ->check(input_file());
  cmd->add_option("--weights", o->weights,
                  "Compensator weights (tpf train: one file, or <stem>.joint<j>.json per joint); "
                  "without: no compensator")
      ->check(weights_path());
  cmd->add_option("--out", o->out, "Log to write: the input with its est_* columns")->required();
  cmd->add_option("--report", o->report,
                  "Plot page to write (default: beside --out, .html instead of .csv)");
  cmd->add_option("--json", o->json, "Episodes and status counts as JSON");
  cmd->add_option("--merge-gap", o->merge_gap_s,
                  "Contacts apart by less than this are one episode [s]")
      ->capture_default_str()
      ->check(non_negative());
  cmd->add_flag("--verbose", o->verbose,
                "List every episode (default: the first 15) and every status bit");
  cmd->callback([o] {
    const std::string report = o->report.empty() ? default_report_path(o->out) : o->report;
    refuse_overwriting_inputs(
        "estimate",
        joined(joined({{"--log", o->log}, {"--estimator", o->estimator}}, model_inputs(o->model)),
               weight_files("--weights", o->weights)),
        {{"--out", o->out}, {"--report", report}, {"--json", o->json}});
    run_estimate(*o, report);
  });
}

}  // namespace tpf::cli

TPF_UNOPTIMISED_WHEN_SANITIZED_END
