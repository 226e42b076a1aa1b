// `tpf import`: foreign CSV files (plain or .gz) → tpf logs, through a column map (JSON).
#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "core/common/unoptimised_when_sanitized.hpp"
#include "offline/log/import_log.hpp"
#include "offline/log/log_writer.hpp"
#include "offline/log/torque_sensor.hpp"
#include "option_validators.hpp"
#include "output_collisions.hpp"
#include "tpf/common/error.hpp"

TPF_UNOPTIMISED_WHEN_SANITIZED_BEGIN

namespace {

struct ImportArgs {
  std::string map, out, out_dir;
  std::vector<std::string> inputs;
  bool compress = true, verbose = false;
};

/// "<dir>/<name without .gz and .csv>.csv.gz" (or .csv).
std::filesystem::path output_in(const std::string& dir, const std::filesystem::path& input,
                                bool compress) {
  std::string name = input.filename().string();
  for (const char* suffix : {".gz", ".csv"})
    if (name.ends_with(suffix)) name.resize(name.size() - std::string_view(suffix).size());
  return std::filesystem::path(dir) / (name + (compress ? ".csv.gz" : ".csv"));
}

/// Recordings printed in full by default; beyond them a recording the import found nothing
/// unusual in (no irregular or dropped step, no reader note, no missing value) gets one line.
constexpr std::size_t kRecordingsInFull = 3;

bool routine(const tpf::offline::ImportReport& report, const tpf::offline::Log& log) {
  return report.irregular_steps == 0 && report.not_increasing == 0 && report.reader_notes.empty() &&
         report.unmatched_rows == 0 && log.quality.missing_total() == 0;
}

/// One recording: map.files inputs joined into one log; `in_full`: every line of its report,
/// else one line when it is routine (its flat or missing torque sensors still said).
void import_one(const tpf::offline::ImportMap& map, const std::vector<std::string>& inputs,
                const std::filesystem::path& output, bool in_full) {
  using namespace tpf::offline;
  ImportReport report;
  const Log log =
      import_log(std::vector<std::filesystem::path>(inputs.begin(), inputs.end()), map, report);
  write_log(output, log);
  std::string names;
  for (const std::string& input : inputs)
    names.append(names.empty() ? "" : " + ").append(input);
  if (!in_full && routine(report, log)) {
    std::printf("import: %s -> %s: %zu rows, step %.6g s, regular\n", names.c_str(),
                output.string().c_str(), report.rows_written, report.nominal_step_s);
    for (const std::string& line : torque_sensor_problems(log, map.joints))
      std::printf("  %s\n", line.c_str());
    return;
  }
  std::printf("import: %s -> %s\n", names.c_str(), output.string().c_str());
  for (const std::string& line : report.lines())
    std::printf("  %s\n", line.c_str());
  if (log.quality.missing_total() > 0)
    std::printf("  %zu missing values (kept as nan)\n", log.quality.missing_total());
  for (const std::string& line : torque_sensor_report(log, map.joints))
    std::printf("  %s\n", line.c_str());
}

/// Inputs come in recordings of `files` each (the map's "files").
void check_output_options(const ImportArgs& a, std::size_t files) {
  if (a.out.empty() == a.out_dir.empty())
    throw tpf::Error("import: give either --out (one recording) or --out-dir");
  if (a.inputs.size() % files != 0)
    throw tpf::Error("import: " + a.map + " reads " + std::to_string(files) +
                     " files per recording; " + std::to_string(a.inputs.size()) +
                     " inputs are not a whole number of recordings");
  if (!a.out.empty() && a.inputs.size() != files)
    throw tpf::Error("import: --out takes one recording (" + std::to_string(files) +
                     " file(s)); use --out-dir for " + std::to_string(a.inputs.size()) + " inputs");
}

/// The log each recording is written to (named after its first file), in input order.
tpf::cli::PathOptions output_files(const ImportArgs& a, std::size_t files) {
  if (!a.out.empty()) return {{"--out", a.out}};
  tpf::cli::PathOptions outputs;
  for (std::size_t k = 0; k < a.inputs.size(); k += files)
    outputs.push_back(
        {"the --out-dir file", output_in(a.out_dir, a.inputs[k], a.compress).string()});
  return outputs;
}

void run_import(const ImportArgs& a) {
  using namespace tpf::cli;
  const tpf::offline::ImportMap map = tpf::offline::load_import_map(a.map);
  const auto files = static_cast<std::size_t>(map.files);
  check_output_options(a, files);
  const PathOptions outputs = output_files(a, files);
  refuse_overwriting_inputs("import", joined({{"--map", a.map}}, each_of("the input", a.inputs)),
                            outputs);
  if (!a.out_dir.empty()) std::filesystem::create_directories(a.out_dir);
  for (std::size_t k = 0; k < outputs.size(); ++k)
    import_one(map,
               std::vector<std::string>(a.inputs.begin() + static_cast<long>(k * files),
                                        a.inputs.begin() + static_cast<long>((k + 1) * files)),
               outputs[k].path, a.verbose || k < kRecordingsInFull);
  if (!a.verbose && outputs.size() > kRecordingsInFull)
    std::printf("(--verbose: every recording's conversions and time steps)\n");
}

}  // namespace

namespace tpf::cli {

void register_import_command(CLI::App& app) {
  auto a = std::make_shared<ImportArgs>();
  CLI::App* cmd =
      app.add_subcommand("import", "Turn foreign CSV files into tpf logs through a column map");
  cmd->footer(
      "Turn foreign CSV files (plain or .gz) into tpf logs with a column map (JSON: time column "
      "and unit or sample rate, q, dq, current or torque, torque sensor, temperature, units, "
      "scale, sign, offset, joint order, several files per recording joined by index or time, "
      "motor-side columns through a transmission, q-dot and q-ddot derived from q; "
      "docs/log-format.md). Reports irregular time stamps and what was done about them, each "
      "conversion, and where the torque sensor is missing or flat"
      "\nExample: tpf import --map data/real/kinova-gen3/kinova.import.json --out-dir logs/ "
      "raw/*.csv.gz");
  cmd->add_option("--map", a->map, "Column map, e.g. data/real/kinova-gen3/kinova.import.json")
      ->required()
      ->check(input_file());
  cmd->add_option("csv", a->inputs,
                  "Foreign CSV file(s), plain or .gz; a map of \"files\": n takes them n at a "
                  "time, the files of one recording in the map's order")
      ->required()
      ->check(input_file());
  cmd->add_option("--out", a->out, "The tpf log to write (one input; .gz: compressed)");
  cmd->add_option("--out-dir", a->out_dir,
                  "Folder for the logs, one per input, named after it (<name>.csv.gz)");
  cmd->add_flag("!--no-gzip", a->compress, "With --out-dir: write plain .csv");
  cmd->add_flag("--verbose", a->verbose,
                "Every recording in full (default: the first 3, then one line each unless its "
                "time steps or values need a word)");
  cmd->callback([a] { run_import(*a); });
}

}  // namespace tpf::cli

TPF_UNOPTIMISED_WHEN_SANITIZED_END
