#include "offline/compensator_training/train_compensator.hpp"

#include <algorithm>
#include <chrono>

#include "offline/compensator_training/baseline_start.hpp"
#include "offline/compensator_training/tcn_parameters.hpp"
#include "offline/compensator_training/training_dataset.hpp"
#include "tpf/common/error.hpp"

namespace tpf::offline {

int compensator_input_channel(std::string_view name) {
  for (int c = 0; c < kCompensatorInputsPerJoint; ++c)
    if (name == kCompensatorInputNames[static_cast<std::size_t>(c)]) return c;
  throw Error::at("compensator training", 0, "input",
                  std::string(name) +
                      " is not a compensator input (q, dq, ddq, static-friction, "
                      "nominal-friction)");
}

namespace {

/// The network input channels of options.masked_inputs: the channel itself in a per-joint network,
/// that input of every joint (c·joints + k) in the all-joints one. Throws on an unknown channel.
std::vector<int> masked_network_inputs(const CompensatorTrainingOptions& options, int joints) {
  std::vector<int> masked;
  for (int c : options.masked_inputs) {
    if (c < 0 || c >= kCompensatorInputsPerJoint)
      throw Error::at("compensator training", 0, "masked_inputs",
                      "channel " + std::to_string(c) + " is not a compensator input");
    for (int k = 0; k < (options.per_joint ? 1 : joints); ++k)
      masked.push_back(options.per_joint ? c : c * joints + k);
  }
  return masked;
}

}  // namespace

CompensatorTraining train_compensator(const std::vector<EstimatorTrace>& traces,
                                      const CompensatorTrainingOptions& options,
                                      const TcnProgressCallback& progress) {
  if (options.per_joint && options.joint_hidden != kPerJointHiddenSmall &&
      options.joint_hidden != kPerJointHiddenLarge)
    throw Error::at(
        "compensator training", 0, "joint_hidden",
        std::to_string(options.joint_hidden) + " channels; per-joint networks are compiled for " +
            std::to_string(kPerJointHiddenSmall) + " or " + std::to_string(kPerJointHiddenLarge));
  if (traces.empty()) throw Error("compensator training: no log to train on");
  const int joints = static_cast<int>(traces.front().dq.cols());
  const auto start = std::chrono::steady_clock::now();
  CompensatorTraining out;
  out.layout = options.per_joint ? CompensatorLayout::PerJoint : CompensatorLayout::AllJoints;
  const int networks = options.per_joint ? joints : 1;
  const std::vector<int> masked = masked_network_inputs(options, joints);
  for (int net = 0; net < networks; ++net) {
    const int joint = options.per_joint ? net : -1;
    TcnDataset dataset;
    TcnTrainOptions o = options.tcn;
    for (const EstimatorTrace& trace : traces) {
      TcnSequence sequence = training_sequence(trace, joint);
      for (int c : masked)
        sequence.inputs.col(c).setZero();
      sequence.weight = regime_weights(trace, joint, options.static_weight,
                                       options.static_to_kinetic_weight, options.regimes);
      dataset.sequences.push_back(std::move(sequence));
    }
    o.architecture.inputs = kCompensatorInputsPerJoint * (options.per_joint ? 1 : joints);
    o.architecture.outputs = options.per_joint ? 1 : joints;
    o.architecture.hidden = options.per_joint ? options.joint_hidden : kAllJointsHidden;
    o.architecture.levels = kCompensatorLevels;
    o.architecture.kernel = kCompensatorKernel;
    if (o.max_seconds > 0) o.max_seconds /= networks;
    if (!o.checkpoint_path.empty() && options.per_joint)
      o.checkpoint_path = joint_weight_path(o.checkpoint_path, joint).string();
    TcnTrainer trainer(dataset, o);
    out.training_windows += trainer.training_windows();
    out.validation_windows += trainer.validation_windows();
    Eigen::VectorXi baseline(o.architecture.outputs);
    for (int k = 0; k < o.architecture.outputs; ++k)
      baseline[k] = options.per_joint ? 3 : 3 * joints + k;
    // The baseline start predicts τ̂_fric,s: not when the networks do not see it.
    const bool sees_static_friction =
        std::find(options.masked_inputs.begin(), options.masked_inputs.end(),
                  kStaticFrictionInput) == options.masked_inputs.end();
    TcnTrainResult result =
        options.start_from_baseline && sees_static_friction
            ? trainer.train(baseline_start(o.architecture, o.seed, trainer.input_mean(),
                                           trainer.input_std(), baseline),
                            progress)
            : trainer.train(progress);
    mask_tcn_inputs(result.best, masked);
    out.files.push_back(to_weight_file(result.best));
    out.results.push_back(std::move(result));
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

std::vector<std::string> write_compensator(const CompensatorTraining& training,
                                           const std::filesystem::path& path) {
  std::vector<std::string> written;
  for (std::size_t k = 0; k < training.files.size(); ++k) {
    const auto p = training.layout == CompensatorLayout::PerJoint
                       ? joint_weight_path(path, static_cast<int>(k))
                       : path;
    if (!p.parent_path().empty()) std::filesystem::create_directories(p.parent_path());
    write_tcn_weight_file(p.string(), training.files[k]);
    written.push_back(p.string());
  }
  return written;
}

}  // namespace tpf::offline
