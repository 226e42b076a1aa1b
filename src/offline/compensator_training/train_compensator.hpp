// Training the arm's friction compensator from contact-free logs: estimator traces → TCN dataset
// → TcnTrainer → weight files (torque inputs and outputs in N·m).
#pragma once

#include <array>
#include <filesystem>
#include <string_view>
#include <vector>

#include "offline/compensator_training/tcn_trainer.hpp"
#include "offline/regimes/regime.hpp"
#include "offline/replay/replay_estimator.hpp"
#include "tpf/nn/tcn_weight_file.hpp"

namespace tpf::offline {

/// Channel of q_j in a joint's compensator input.
inline constexpr int kPositionInput = 0;
/// Channel of τ̂_fric,s,j (the static-friction estimate) in a joint's compensator input.
inline constexpr int kStaticFrictionInput = 3;

/// Names of a joint's compensator inputs by channel: q, dq, ddq, static-friction,
/// nominal-friction (what tpf train --without-input takes).
inline constexpr std::array<const char*, kCompensatorInputsPerJoint> kCompensatorInputNames{
    "q", "dq", "ddq", "static-friction", "nominal-friction"};

/// The channel of an input named as in kCompensatorInputNames; throws tpf::Error otherwise.
int compensator_input_channel(std::string_view name);

struct CompensatorTrainingOptions {
  /// Trainer options; the architecture is set from the layout (inputs, outputs, hidden, levels =
  /// the networks the tools evaluate, any_compensator.hpp). max_seconds is the whole
  /// safety net.
  TcnTrainOptions tcn;
  bool per_joint = false;  ///< one network per joint instead of one for all joints
  /// Hidden channels of a per-joint network: kPerJointHiddenSmall or kPerJointHiddenLarge (the
  /// all-joints network has kAllJointsHidden).
  int joint_hidden = kPerJointHiddenSmall;
  /// Start from baseline_start (the network predicts τ̂_fric,s) instead of a random network
  /// (ignored when static-friction is a masked input).
  bool start_from_baseline = true;
  /// Per-sample loss weights by regime (regime_weights): break-away and rest count this many
  /// times a moving sample.
  double static_to_kinetic_weight = 10.0;
  double static_weight = 3.0;
  /// Input channels per joint (0 q, 1 q̇, 2 q̈, 3 τ̂_fric,s, 4 τ_fric,nom) the networks must not
  /// see: held at 0 in training and removed from block 0 of the written networks
  /// (mask_tcn_inputs), so the output does not depend on them. E.g. {kPositionInput}: friction
  /// memory that does not depend on where the joint is (tpf train --without-input q).
  std::vector<int> masked_inputs;
  /// Labelling of the regimes for the weights (the static-to-kinetic window after |q̇| crosses
  /// static_velocity lasts fallback_transition_s).
  RegimeOptions regimes;
};

struct CompensatorTraining {
  CompensatorLayout layout = CompensatorLayout::AllJoints;
  std::vector<TcnWeightFile> files;     ///< one, or one per joint; outputs in N·m
  std::vector<TcnTrainResult> results;  ///< per network
  std::size_t training_windows = 0, validation_windows = 0;
  double seconds = 0.0;  ///< wall-clock training time
};

/// Trains on the traces of contact-free logs (training_sequence of each, weighted by
/// regime_weights), with the trainer's zero-phase split, Adam, held-out blocks and early stopping;
/// per joint, each network gets max_epochs and max_seconds/N. The joint count N is the traces'.
/// The threads (options.tcn.threads) share whole networks: as many train at once as there are
/// threads, up to N (the same networks as one after another; progress calls are serialised).
/// Inputs and outputs in N·m (the traces' units).
CompensatorTraining train_compensator(const std::vector<EstimatorTrace>& traces,
                                      const CompensatorTrainingOptions& options,
                                      const TcnProgressCallback& progress = {});

/// Writes the weight files: `path` (all joints) or joint_weight_path(path, j) (per joint).
/// Returns the paths written.
std::vector<std::string> write_compensator(const CompensatorTraining& training,
                                           const std::filesystem::path& path);

}  // namespace tpf::offline
