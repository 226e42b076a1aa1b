// Training of the friction-compensator TCN on in-memory sequences (offline, multi-threaded).
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <functional>
#include <iosfwd>
#include <string>
#include <type_traits>
#include <vector>

#include "offline/compensator_training/adam.hpp"
#include "offline/compensator_training/tcn_parameters.hpp"
#include "offline/compensator_training/tcn_window_model.hpp"

namespace tpf::offline {

/// One contiguous recording at the options' sample rate.
struct TcnSequence {
  /// T × In, one row per sample; per joint [q rad, q̇ rad/s, q̈ rad/s², τ̂_fric,s N·m
  /// (0 while moving)], joints side by side for the all-joints network.
  Eigen::MatrixXd inputs;
  /// T × Out: the residual of the nominal model τ_meas − (τ_dyn + τ_fric) [N·m], the target of
  /// Tcn::output(). Contact-free data only (there it is the friction truth).
  Eigen::MatrixXd residual;
  /// T × Out per-sample loss weights ≥ 0 (e.g. to emphasise break-away); empty: all 1.
  Eigen::MatrixXd weight;
};

struct TcnDataset {
  std::vector<TcnSequence> sequences;
};

struct TcnTrainOptions {
  TcnArchitecture architecture;
  double sample_rate_hz = 400.0;
  /// Cut-off of the zero-phase split of the residual r: low = filtfilt of r with a 2nd-order
  /// Butterworth (offline/signal/butterworth.hpp, forward–backward), high = r − low.
  double split_cutoff_hz = 2.0;
  /// loss = weight_low·MSE(low − target_low) + weight_high·MSE(high − target_high), each MSE
  /// weighted per sample by TcnSequence::weight (Σ w·e² / Σ w).
  double weight_low = 1.0;
  double weight_high = 1.0;
  /// Supervised steps per window; a window holds R − 1 + window_outputs inputs.
  int window_outputs = 256;
  /// Windows per Adam step.
  int batch_windows = 8;
  AdamOptimizer::Settings adam;
  /// At most this many training windows per epoch (≤ 0: all). A pass over the shuffled training
  /// windows is split into P = ⌈N/epoch_windows⌉ epochs of ⌊N/P⌋ windows each (the N mod P
  /// windows left at the end of a pass wait for the next shuffle); the held-out loss, the
  /// learning-rate decay and early stopping act after each epoch. With N ≤ epoch_windows an
  /// epoch is one pass over all windows, as without it.
  int epoch_windows = 0;
  int max_epochs = 200;
  /// Halve the learning rate when the validation loss has not improved for this many epochs
  /// (and again after as many more); ≤ 0: constant rate.
  int decay_patience = 4;
  /// Stop when the validation loss has not improved for this many epochs.
  int patience = 15;
  /// Stop (converged, counted as an early stop) when the decay would halve the learning rate
  /// below this; ≤ 0: never. Up to that epoch nothing changes. With the default rate 2e-3 and
  /// 5e-5 the sixth decay ends training: on the 30-minute twin log the held-out loss then was
  /// within 1 % of training on to patience, at ≈ 3/4 of the epochs (docs/tcn-performance.md).
  double min_learning_rate = 0.0;
  /// Stop after the epoch that crosses this wall-clock budget [s]; ≤ 0: no budget. Results then
  /// depend on the machine's speed: use max_epochs for a reproducible budget and this only as a
  /// safety net (TcnTrainResult::stopped_on_time says when it triggered).
  double max_seconds = 0.0;
  /// Share of the windows held out for early stopping: whole blocks of validation_block_windows
  /// consecutive windows (a seeded choice of blocks), so held-out data is contiguous in time; the
  /// window after a block boundary starts its inputs at the boundary, so no training window's
  /// inputs or targets overlap a held-out window's.
  double validation_fraction = 0.15;
  int validation_block_windows = 8;
  std::uint64_t seed = 1;
  /// Evaluate windows (forward and backward) in float, ≈ 2× faster; the parameters, the Adam
  /// state, the gradient reduction and the reported losses stay in double.
  bool single_precision = true;
  /// Worker threads. Results do not depend on it: the gradient of a batch is reduced over a fixed
  /// number of chunks in a fixed order.
  int threads = 2;
  /// If not empty, the best model so far is written there (weight-file format) at each improvement.
  std::string checkpoint_path;
};

/// What the progress callback receives after each epoch (losses are the weighted MSE above).
struct TcnTrainProgress {
  int epoch = 0;  ///< 1-based
  int max_epochs = 0;
  double train_loss = 0.0;  ///< mean over the epoch's batches
  double validation_loss = 0.0;
  double best_validation_loss = 0.0;
  int best_epoch = 0;
  double elapsed_seconds = 0.0;
  double remaining_seconds = 0.0;  ///< upper estimate (max_epochs or the time budget)
  double learning_rate = 0.0;      ///< Adam step size used in this epoch
  bool last = false;               ///< training stops after this epoch
  /// Which network (0-based): train_compensator sets the joint of a per-joint network, so that
  /// the reports of networks training at once can be told apart; 0 otherwise.
  int network = 0;
};

using TcnProgressCallback = std::function<void(const TcnTrainProgress&)>;

struct TcnTrainResult {
  TcnParameters best;  ///< parameters of the best validation epoch
  std::vector<TcnTrainProgress> history;
  int best_epoch = 0;
  double best_validation_loss = 0.0;
  bool stopped_early = false;    ///< patience ran out (not max_epochs nor the time budget)
  bool stopped_on_time = false;  ///< the wall-clock safety net max_seconds ended training
};

/// Prepares the data once (NaN rows flagged and skipped by cutting the sequence there, target
/// split, normalisation, windows, held-out set), then trains with Adam and early stopping.
/// Deterministic for a given seed.
class TcnTrainer {
 public:
  /// Throws tpf::Error naming the sequence and field on inconsistent shapes, and if fewer than
  /// two windows of R samples remain.
  TcnTrainer(const TcnDataset& dataset, const TcnTrainOptions& options);

  /// Trains from init_tcn_parameters(architecture, seed), or from `start` if given (its
  /// normalisation is replaced by this dataset's, so start from parameters of similar data).
  TcnTrainResult train(const TcnProgressCallback& progress = {});
  TcnTrainResult train(TcnParameters start, const TcnProgressCallback& progress = {});

  /// Weighted MSE of `parameters` over the training or the held-out windows.
  double loss(const TcnParameters& parameters, bool validation) const;

  /// Mean normalisation μ, σ of the inputs (σ = 1 for a constant channel).
  const Eigen::VectorXd& input_mean() const { return input_mean_; }
  const Eigen::VectorXd& input_std() const { return input_std_; }
  /// Rows dropped because an input or residual value was not finite.
  Eigen::Index skipped_samples() const { return skipped_samples_; }
  std::size_t training_windows() const { return training_.size(); }
  std::size_t validation_windows() const { return validation_.size(); }

  /// Training windows in one epoch of N windows with TcnTrainOptions::epoch_windows = cap: N if
  /// cap ≤ 0 or N ≤ cap, else ⌊N/P⌋ with P = ⌈N/cap⌉ epochs per pass.
  static std::size_t windows_per_epoch(std::size_t windows, int epoch_windows);

  /// Where a window lies: samples [first_input, end) of finite run `segment` (runs numbered in
  /// dataset order), supervising [first_output, end).
  struct WindowSpan {
    int segment;
    Eigen::Index first_input, first_output, end;
  };
  /// The spans of the training or the held-out windows.
  std::vector<WindowSpan> window_spans(bool validation) const;

 private:
  template <typename S>
  struct Segment {
    Eigen::Matrix<S, Eigen::Dynamic, Eigen::Dynamic> inputs;  ///< In × T, normalised
    Eigen::Matrix<S, Eigen::Dynamic, Eigen::Dynamic> low;     ///< Out × T
    Eigen::Matrix<S, Eigen::Dynamic, Eigen::Dynamic> high;    ///< Out × T
    Eigen::Matrix<S, Eigen::Dynamic, Eigen::Dynamic> scale;   ///< Out × T, √weight; empty: 1
  };
  struct Window {
    int segment;
    Eigen::Index first_output;  ///< segment column of the first supervised step
    Eigen::Index outputs;
    double weight;  ///< Σ of the sample weights of its Out × outputs targets
  };

  /// Σ over `windows` of the window loss (and gradient into `gradient` if not null), computed in
  /// kChunks fixed chunks on options_.threads threads and reduced in chunk order.
  double sum_loss(const TcnParameters& parameters, const std::vector<Window>& windows,
                  TcnParameters* gradient) const;
  template <typename S>
  double sum_loss_in(const BasicTcnParameters<S>& parameters,
                     const std::vector<Segment<S>>& segments, const std::vector<Window>& windows,
                     TcnParameters* gradient) const;
  /// Σ of the windows' sample weights (the normaliser of the weighted MSE).
  static double weight_sum(const std::vector<Window>& windows);

  static constexpr int kChunks = 4;
  /// Chunk c's window buffers, kept from one batch to the next so that a batch allocates
  /// nothing for its windows. Each chunk runs on one thread at a time; sum_loss is not for
  /// concurrent calls on one trainer.
  template <typename S>
  std::array<BasicTcnWindowWorkspace<S>, kChunks>& workspaces() const {
    if constexpr (std::is_same_v<S, float>) {
      return float_workspaces_;
    } else {
      return workspaces_;
    }
  }

  TcnTrainOptions options_;
  mutable std::array<BasicTcnWindowWorkspace<double>, kChunks> workspaces_;
  mutable std::array<BasicTcnWindowWorkspace<float>, kChunks> float_workspaces_;
  std::vector<Segment<double>> segments_;
  std::vector<Segment<float>> float_segments_;  ///< copies for single_precision
  std::vector<Window> training_;
  std::vector<Window> validation_;
  Eigen::VectorXd input_mean_;
  Eigen::VectorXd input_std_;
  Eigen::Index skipped_samples_ = 0;
};

/// TcnTrainer(dataset, options).train(progress).
TcnTrainResult train_tcn(const TcnDataset& dataset, const TcnTrainOptions& options,
                         const TcnProgressCallback& progress = {});

/// A callback drawing a TerminalProgressBar on `out` ("epoch 12/200  loss …  val …  ETA …"),
/// redrawn in place when `redraw` (a terminal), else a line per network at each tenth of its
/// epochs.
TcnProgressCallback tcn_progress_bar(std::ostream& out, bool redraw = true);

}  // namespace tpf::offline
