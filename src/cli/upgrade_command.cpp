// `tpf upgrade`: parameter, estimator and weight files of the earlier format (efforts in the
// log's unit) converted in place to today's, every torque in N·m.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <memory>
#include <string>

#include "commands.hpp"
#include "core/common/unoptimised_when_sanitized.hpp"
#include "offline/upgrade/upgrade_files.hpp"
#include "option_validators.hpp"
#include "output_collisions.hpp"

TPF_UNOPTIMISED_WHEN_SANITIZED_BEGIN

namespace tpf::cli {

void register_upgrade_command(CLI::App& app) {
  auto params = std::make_shared<std::string>(), estimator = std::make_shared<std::string>(),
       weights = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand(
      "upgrade", "Convert version-1 parameter, estimator and weight files to N*m, in place");
  cmd->footer(
      "Convert, in place, a version-1 parameter file (friction and added effects in the log's "
      "effort unit, e.g. mA) and the estimator parameters and compensator weights made with it "
      "to today's files, every torque in N*m (exact: divided by the file's own "
      "effort_per_newton_metre). Converts every file or none"
      "\nExample: tpf upgrade --params old.params.json --estimator old.estimator.json --weights "
      "old.tcn.json");
  cmd->add_option("--params", *params, "tpf-params file, version 1 (holds the unit factor)")
      ->required()
      ->check(input_file());
  cmd->add_option("--estimator", *estimator,
                  "tpf-estimator file, version 2, calibrated with that model")
      ->check(input_file());
  cmd->add_option("--weights", *weights,
                  "compensator weights trained with that model: one file, or the path whose "
                  "<stem>.joint<j>.json files exist (as `tpf train --per-joint --out` names them)")
      ->check(weights_path());
  cmd->callback([=] {
    // Each file is converted in place, on purpose; two options naming one file would write it
    // twice.
    refuse_overwriting_inputs("upgrade", {},
                              joined({{"--params", *params}, {"--estimator", *estimator}},
                                     weight_files("--weights", *weights)));
    const tpf::offline::UpgradeFiles files{*params, *estimator, *weights};
    for (const std::string& line : tpf::offline::upgrade_files(files))
      std::printf("upgrade: wrote %s\n", line.c_str());
  });
}

}  // namespace tpf::cli

TPF_UNOPTIMISED_WHEN_SANITIZED_END
