#include "offline/compensator_training/train_compensator.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <exception>
#include <mutex>
#include <thread>

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

namespace {

/// One trained network and its window counts.
struct TrainedNetwork {
  TcnTrainResult result;
  std::size_t training_windows = 0, validation_windows = 0;
};

/// Trains network `net` (joint `net` per joint, else the all-joints one) with `threads` threads.
TrainedNetwork train_network(const std::vector<EstimatorTrace>& traces,
                             const CompensatorTrainingOptions& options,
                             const std::vector<int>& masked, int networks, int net, int threads,
                             const TcnProgressCallback& progress) {
  const int joints = static_cast<int>(traces.front().dq.cols());
  const int joint = options.per_joint ? net : -1;
  TcnDataset dataset;
  TcnTrainOptions o = options.tcn;
  o.threads = threads;
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
  TrainedNetwork out;
  out.training_windows = trainer.training_windows();
  out.validation_windows = trainer.validation_windows();
  Eigen::VectorXi baseline(o.architecture.outputs);
  for (int k = 0; k < o.architecture.outputs; ++k)
    baseline[k] = options.per_joint ? 3 : 3 * joints + k;
  // The baseline start predicts τ̂_fric,s: not when the networks do not see it.
  const bool sees_static_friction =
      std::find(options.masked_inputs.begin(), options.masked_inputs.end(), kStaticFrictionInput) ==
      options.masked_inputs.end();
  TcnProgressCallback report;
  if (progress)
    report = [&progress, net](const TcnTrainProgress& p) {
      TcnTrainProgress named = p;
      named.network = net;
      progress(named);
    };
  out.result = options.start_from_baseline && sees_static_friction
                   ? trainer.train(baseline_start(o.architecture, o.seed, trainer.input_mean(),
                                                  trainer.input_std(), baseline),
                                   report)
                   : trainer.train(report);
  mask_tcn_inputs(out.result.best, masked);
  return out;
}

/// Trains every network: up to one network per thread at once (each on threads / networks at
/// once of them, at least 1), so the threads share whole networks rather than each batch. A
/// network's training is deterministic whatever its thread count, so the schedule changes no
/// result; progress reports are serialised.
std::vector<TrainedNetwork> train_networks(const std::vector<EstimatorTrace>& traces,
                                           const CompensatorTrainingOptions& options,
                                           const std::vector<int>& masked, int networks,
                                           const TcnProgressCallback& progress) {
  const int concurrent = std::clamp(options.tcn.threads, 1, networks);
  const int threads_each = std::max(1, options.tcn.threads / concurrent);
  std::mutex progress_mutex;
  TcnProgressCallback report;
  if (progress)
    report = [&](const TcnTrainProgress& p) {
      const std::lock_guard<std::mutex> lock(progress_mutex);
      progress(p);
    };
  std::vector<TrainedNetwork> trained(static_cast<std::size_t>(networks));
  std::vector<std::exception_ptr> errors(static_cast<std::size_t>(networks));
  std::atomic<int> next{0};
  auto worker = [&] {
    for (int net = next++; net < networks; net = next++) {
      try {
        trained[static_cast<std::size_t>(net)] =
            train_network(traces, options, masked, networks, net, threads_each, report);
      } catch (...) {
        errors[static_cast<std::size_t>(net)] = std::current_exception();
      }
    }
  };
  std::vector<std::thread> helpers;
  for (int w = 1; w < concurrent; ++w)
    helpers.emplace_back(worker);
  worker();
  for (std::thread& h : helpers)
    h.join();
  for (const std::exception_ptr& e : errors)
    if (e) std::rethrow_exception(e);
  return trained;
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
  if (options.tcn.threads < 1) throw Error::at("TCN training", 0, "options.threads", "must be ≥ 1");
  const int joints = static_cast<int>(traces.front().dq.cols());
  const auto start = std::chrono::steady_clock::now();
  CompensatorTraining out;
  out.layout = options.per_joint ? CompensatorLayout::PerJoint : CompensatorLayout::AllJoints;
  const int networks = options.per_joint ? joints : 1;
  const std::vector<int> masked = masked_network_inputs(options, joints);
  for (TrainedNetwork& n : train_networks(traces, options, masked, networks, progress)) {
    out.training_windows += n.training_windows;
    out.validation_windows += n.validation_windows;
    out.files.push_back(to_weight_file(n.result.best));
    out.results.push_back(std::move(n.result));
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
