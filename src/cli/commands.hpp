// Each subcommand of `tpf` lives in its own file and registers itself on the app.
#pragma once

#include <CLI/CLI.hpp>

namespace tpf::cli {

void register_info_command(CLI::App& app);
void register_demo_command(CLI::App& app);
void register_simulate_command(CLI::App& app);
void register_identify_command(CLI::App& app);
void register_diagnose_command(CLI::App& app);
void register_train_command(CLI::App& app);
void register_evaluate_command(CLI::App& app);
void register_calibrate_command(CLI::App& app);
void register_import_command(CLI::App& app);
void register_validate_command(CLI::App& app);
void register_upgrade_command(CLI::App& app);
void register_estimate_command(CLI::App& app);

/// Prints a robot file's model, drives, pads and a few computed quantities (used by info and demo).
void print_robot_summary(const std::string& robot_file);

}  // namespace tpf::cli
