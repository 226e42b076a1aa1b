// `tpf demo`: the main job. It grows into the whole loop on the digital twin
// (simulate → identify → diagnose → train → evaluate → report); today it loads the arm and prints
// it.
#include <filesystem>
#include <iostream>

#include "commands.hpp"
#include "offline/common/data_files.hpp"

namespace tpf::cli {

void register_demo_command(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "demo", "Run the whole loop on the digital twin and write a report (the README's main job)");
  auto out = std::make_shared<std::string>("tpf-demo");
  cmd->add_option("--out", *out, "output folder for logs, parameters and the report")
      ->capture_default_str();
  cmd->callback([out] {
    std::filesystem::create_directories(*out);
    std::cout << "tpf demo (output in " << *out << ")\n\n";
    print_robot_summary(offline::data_file("arm4.robot.json").string());
  });
}

}  // namespace tpf::cli
