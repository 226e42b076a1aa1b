// The files every estimator-running command is built from: --params (required), --robot and
// --pads (defaulting to the twin arm's files in data/).
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "offline/common/data_files.hpp"

namespace tpf::cli {

/// Adds --params, --robot and --pads to `cmd`, writing into the given strings; --robot and --pads
/// start at data/arm4.robot.json and data/arm4.pads.json.
inline void add_model_file_options(CLI::App* cmd, std::string& params, std::string& robot,
                                   std::string& pads, const std::string& params_help) {
  robot = offline::data_file("arm4.robot.json").string();
  pads = offline::data_file("arm4.pads.json").string();
  cmd->add_option("--params", params, params_help)->required()->check(CLI::ExistingFile);
  cmd->add_option("--robot", robot, "Robot file")->capture_default_str()->check(CLI::ExistingFile);
  cmd->add_option("--pads", pads, "Pad layout file")
      ->capture_default_str()
      ->check(CLI::ExistingFile);
}

}  // namespace tpf::cli
