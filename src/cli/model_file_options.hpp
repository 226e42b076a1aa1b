// The files every estimator-running command is built from: --params (required), --robot
// (defaulting to the twin arm's file in data/) and --pads (defaulting to the layout the robot file
// names; "none" or a robot file without one: no skin).
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "offline/common/data_files.hpp"
#include "offline/common/run_time_types.hpp"
#include "option_validators.hpp"
#include "output_collisions.hpp"
#include "tpf/estimation/load_estimator.hpp"
#include "tpf/estimation/nominal_model.hpp"
#include "tpf/model/robot_description.hpp"
#include "tpf/skin/pad_layout.hpp"

namespace tpf::cli {

struct ModelFiles {
  std::string params;
  std::string robot;
  std::string pads;  ///< empty: the robot file's layout; "none": no skin
};

/// Adds --params, --robot and (when `with_pads`) --pads to `cmd`; --robot starts at
/// data/arm4.robot.json.
inline void add_model_file_options(CLI::App* cmd, ModelFiles& files, const std::string& params_help,
                                   bool with_pads = true) {
  files.robot = offline::data_file("arm4.robot.json").string();
  cmd->add_option("--params", files.params, params_help)->required()->check(input_file());
  cmd->add_option("--robot", files.robot, "Robot file (tpf-robot: URDF, drives, pad layout)")
      ->capture_default_str()
      ->check(input_file());
  if (with_pads)
    cmd->add_option("--pads", files.pads,
                    "Pad layout file (default: the one the robot file names; \"none\": no skin)")
        ->check(input_file_or("none"));
}

/// The model files as inputs of refuse_overwriting_inputs (--pads none: not a file).
inline PathOptions model_inputs(const ModelFiles& files) {
  return {{"--params", files.params},
          {"--robot", files.robot},
          {"--pads", files.pads == "none" ? std::string() : files.pads}};
}

/// The pad layout to use: --pads, else the robot file's (empty: no skin).
inline std::string pad_layout_file(const ModelFiles& files, const RobotDescription& robot) {
  if (files.pads == "none") return {};
  if (!files.pads.empty()) return files.pads;
  return robot.pads_file.string();
}

/// "11 pads (data/arm4.pads.json)" or "no skin".
inline std::string describe_pads(std::size_t pads, const std::string& file) {
  return pads == 0 ? std::string("no skin") : std::to_string(pads) + " pads (" + file + ")";
}

/// The estimator set-up of the robot file's arm (its joint count) from the model files, with
/// the default estimator parameters of that count (the tools derive or calibrate them): nominal
/// model, pad layout (pad_layout_file; `with_pads` false: no skin), compensator weights
/// (`weights` empty: none).
inline EstimatorSetup<Eigen::Dynamic> load_model_setup(const ModelFiles& files,
                                                       const std::string& weights,
                                                       bool with_pads = true) {
  const RobotDescription robot = load_robot_description(files.robot);
  EstimatorSetup<Eigen::Dynamic> setup;
  setup.nominal = load_nominal_model(files.params, robot);
  const int joints = setup.nominal.model.joint_count();
  setup.parameters.resize(joints);
  const std::string pads = with_pads ? pad_layout_file(files, robot) : std::string();
  if (!pads.empty()) setup.pads = load_pads(pads, setup.nominal.model);
  setup.weights = find_compensator_weights(weights, joints);
  return setup;
}

}  // namespace tpf::cli
