// Training the arm's friction compensator from contact-free logs: estimator traces → TCN dataset
// → TcnTrainer → weight files in the effort unit.
#pragma once

#include <filesystem>
#include <vector>

#include "offline/train/tcn_trainer.hpp"
#include "offline/training/arm_estimator.hpp"
#include "tpf/nn/tcn_weight_file.hpp"

namespace tpf::offline {

struct CompensatorTrainingOptions {
  /// Trainer options; architecture.inputs/outputs are set from the layout, hidden and levels must
  /// stay kArmHidden/kArmLevels (the compiled networks). max_seconds is the whole budget.
  TcnTrainOptions tcn;
  bool per_joint = false;  ///< one network per joint instead of one for all joints
  /// Start from baseline_start (the network predicts τ̂_fric,s) instead of a random network.
  bool start_from_baseline = true;
  /// Copies of onset_sequences (one window per motion onset, starting onset_lead rows before it)
  /// added to the data to weigh the static-to-kinetic transition; 0: none.
  int onset_copies = 1;
  int onset_lead = 16;
};

struct CompensatorTraining {
  CompensatorLayout layout = CompensatorLayout::AllJoints;
  std::vector<TcnWeightFile> files;     ///< one, or one per joint; heads in the effort unit
  std::vector<TcnTrainResult> results;  ///< per network
  std::size_t training_windows = 0, validation_windows = 0;
  double seconds = 0.0;  ///< wall-clock training time
};

/// Trains on the traces of contact-free logs (training_sequence of each), with the trainer's
/// zero-phase split, Adam, held-out windows and early stopping; per joint, each network gets
/// max_seconds/N. The best parameters are scaled to the effort unit (scale_tcn_outputs).
CompensatorTraining train_compensator(const std::vector<EstimatorTrace>& traces,
                                      const Eigen::VectorXd& effort_per_newton_metre,
                                      const CompensatorTrainingOptions& options,
                                      const TcnProgressCallback& progress = {});

/// Writes the weight files: `path` (all joints) or joint_weight_path(path, j) (per joint).
/// Returns the paths written.
std::vector<std::string> write_compensator(const CompensatorTraining& training,
                                           const std::filesystem::path& path);

}  // namespace tpf::offline
