// `tpf import`: foreign CSV files (plain or .gz) → tpf logs, through a column map (JSON).
#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "offline/log/import_log.hpp"
#include "offline/log/log_writer.hpp"
#include "offline/log/torque_sensor.hpp"
#include "option_validators.hpp"
#include "output_collisions.hpp"
#include "tpf/common/error.hpp"

namespace {

struct ImportArgs {
  std::string map, out, out_dir;
  std::vector<std::string> inputs;
  bool compress = true;
};

/// "<dir>/<name without .gz and .csv>.csv.gz" (or .csv).
std::filesystem::path output_in(const std::string& dir, const std::filesystem::path& input,
                                bool compress) {
  std::string name = input.filename().string();
  for (const char* suffix : {".gz", ".csv"})
    if (name.ends_with(suffix)) name.resize(name.size() - std::string_view(suffix).size());
  return std::filesystem::path(dir) / (name + (compress ? ".csv.gz" : ".csv"));
}

void import_one(const tpf::offline::ImportMap& map, const std::string& input,
                const std::filesystem::path& output) {
  using namespace tpf::offline;
  ImportReport report;
  const Log log = import_log(input, map, report);
  write_log(output, log);
  std::printf("import: %s -> %s\n", input.c_str(), output.string().c_str());
  for (const std::string& line : report.lines())
    std::printf("  %s\n", line.c_str());
  if (log.quality.missing_total() > 0)
    std::printf("  %zu missing values (kept as nan)\n", log.quality.missing_total());
  for (const std::string& line : torque_sensor_report(log, map.joints))
    std::printf("  %s\n", line.c_str());
}

void check_output_options(const ImportArgs& a) {
  if (a.out.empty() == a.out_dir.empty())
    throw tpf::Error("import: give either --out (one input) or --out-dir");
  if (!a.out.empty() && a.inputs.size() != 1)
    throw tpf::Error("import: --out takes one input; use --out-dir for " +
                     std::to_string(a.inputs.size()));
}

/// The log each input is written to, in input order.
tpf::cli::PathOptions output_files(const ImportArgs& a) {
  if (!a.out.empty()) return {{"--out", a.out}};
  tpf::cli::PathOptions outputs;
  for (const std::string& input : a.inputs)
    outputs.push_back({"the --out-dir file", output_in(a.out_dir, input, a.compress).string()});
  return outputs;
}

void run_import(const ImportArgs& a) {
  using namespace tpf::cli;
  check_output_options(a);
  const PathOptions outputs = output_files(a);
  refuse_overwriting_inputs("import", joined({{"--map", a.map}}, each_of("the input", a.inputs)),
                            outputs);
  const tpf::offline::ImportMap map = tpf::offline::load_import_map(a.map);
  if (!a.out_dir.empty()) std::filesystem::create_directories(a.out_dir);
  for (std::size_t k = 0; k < a.inputs.size(); ++k)
    import_one(map, a.inputs[k], outputs[k].path);
}

}  // namespace

namespace tpf::cli {

void register_import_command(CLI::App& app) {
  auto a = std::make_shared<ImportArgs>();
  CLI::App* cmd = app.add_subcommand(
      "import",
      "Turn foreign CSV files (plain or .gz) into tpf logs with a column map (JSON: time column "
      "and unit or sample rate, q, dq, current or torque, torque sensor, temperature, units, "
      "joint order; docs/log-format.md). Reports irregular time stamps and what was done about "
      "them, and where the torque sensor is missing or flat");
  cmd->add_option("--map", a->map, "Column map, e.g. data/real/kinova-gen3/kinova.import.json")
      ->required()
      ->check(input_file());
  cmd->add_option("csv", a->inputs, "Foreign CSV file(s), plain or .gz")
      ->required()
      ->check(input_file());
  cmd->add_option("--out", a->out, "The tpf log to write (one input; .gz: compressed)");
  cmd->add_option("--out-dir", a->out_dir,
                  "Folder for the logs, one per input, named after it (<name>.csv.gz)");
  cmd->add_flag("!--no-gzip", a->compress, "With --out-dir: write plain .csv");
  cmd->callback([a] { run_import(*a); });
}

}  // namespace tpf::cli
