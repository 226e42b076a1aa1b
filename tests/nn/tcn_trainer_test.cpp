// Trainer: overfits a tiny set, is deterministic, and its file loads into the core engine.
#include "offline/compensator_training/tcn_trainer.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <limits>
#include <memory>

#include "offline/compensator_training/synthetic_friction_data.hpp"
#include "tcn_test_support.hpp"
#include "tpf/common/error.hpp"
#include "tpf/nn/load_tcn_weights.hpp"

namespace tpf::offline {
namespace {

TcnTrainOptions small_options() {
  TcnTrainOptions o;
  o.architecture = {4, 8, 3, 4, 1};  // R = 22
  o.window_outputs = 64;
  o.batch_windows = 4;
  o.max_epochs = 4;
  o.seed = 7;
  return o;
}

TEST(TcnTrainer, OverfitsATinySetToNearZeroLoss) {
  TcnDataset data;
  data.sequences.push_back(make_synthetic_friction_sequence(0.4, 400.0, 3, 0.0));  // 160, noiseless
  TcnTrainOptions o = small_options();
  o.architecture.hidden = 16;
  o.window_outputs = 70;  // two windows: one trained, one held out
  o.validation_block_windows = 1;
  o.batch_windows = 1;
  o.max_epochs = 350;
  o.patience = o.max_epochs;
  o.decay_patience = 0;  // the held-out window cannot improve while memorising
  o.adam.learning_rate = 3e-3;
  TcnTrainer trainer(data, o);
  ASSERT_EQ(trainer.training_windows(), 1u);
  const TcnParameters start = init_tcn_parameters(o.architecture, o.seed);
  const double initial = trainer.loss(start, false);
  const TcnTrainResult result = trainer.train(start);
  EXPECT_LT(result.history.back().train_loss, 1e-4 * initial)
      << "initial " << initial << ", final " << result.history.back().train_loss;
}

TEST(TcnTrainer, IsDeterministicWhateverTheThreadCount) {
  TcnDataset data;
  data.sequences.push_back(make_synthetic_friction_sequence(6.0, 400.0, 1));
  TcnTrainOptions o = small_options();
  o.threads = 1;
  const TcnTrainResult one = train_tcn(data, o);
  o.threads = 2;
  const TcnTrainResult two = train_tcn(data, o);
  TcnParameters a = one.best, b = two.best;
  EXPECT_EQ(flatten(a), flatten(b));
  EXPECT_EQ(one.best_validation_loss, two.best_validation_loss);
  ASSERT_EQ(one.history.size(), two.history.size());
  EXPECT_LT(one.history.back().train_loss, one.history.front().train_loss);
}

TEST(TcnTrainer, EpochWindowsSplitAPassIntoEqualEpochs) {
  EXPECT_EQ(TcnTrainer::windows_per_epoch(9532, 0), 9532u);     // no cap
  EXPECT_EQ(TcnTrainer::windows_per_epoch(9532, 9532), 9532u);  // cap = N: one pass per epoch
  EXPECT_EQ(TcnTrainer::windows_per_epoch(9532, 20000), 9532u);
  EXPECT_EQ(TcnTrainer::windows_per_epoch(9532, 2048), 1906u);  // 5 epochs per pass, 2 left over
  EXPECT_EQ(TcnTrainer::windows_per_epoch(10, 3), 2u);          // 4 epochs of 2
  EXPECT_EQ(TcnTrainer::windows_per_epoch(10, 5), 5u);          // 2 epochs of 5
}

TEST(TcnTrainer, EpochWindowsChangeNothingUpToTheTrainingSetAndStayDeterministicBelow) {
  TcnDataset data;
  data.sequences.push_back(make_synthetic_friction_sequence(6.0, 400.0, 1));
  TcnTrainOptions o = small_options();
  o.max_epochs = 6;
  const TcnTrainResult all = train_tcn(data, o);
  const std::size_t n = TcnTrainer(data, o).training_windows();
  ASSERT_GT(n, 8u);
  o.epoch_windows = static_cast<int>(n);
  const TcnTrainResult capped_at_n = train_tcn(data, o);
  TcnParameters a = all.best, b = capped_at_n.best;
  EXPECT_EQ(flatten(a), flatten(b));
  ASSERT_EQ(all.history.size(), capped_at_n.history.size());
  for (std::size_t e = 0; e < all.history.size(); ++e) {
    EXPECT_EQ(all.history[e].train_loss, capped_at_n.history[e].train_loss);
    EXPECT_EQ(all.history[e].validation_loss, capped_at_n.history[e].validation_loss);
  }

  o.epoch_windows = static_cast<int>(n / 3);  // 3 or 4 epochs per pass
  o.threads = 1;
  const TcnTrainResult one = train_tcn(data, o);
  o.threads = 2;
  const TcnTrainResult two = train_tcn(data, o);
  TcnParameters c = one.best, d = two.best;
  EXPECT_EQ(flatten(c), flatten(d));
  ASSERT_EQ(one.history.size(), two.history.size());
  for (std::size_t e = 0; e < one.history.size(); ++e)
    EXPECT_EQ(one.history[e].validation_loss, two.history[e].validation_loss);
  EXPECT_NE(flatten(a), flatten(c));  // fewer steps per epoch: another trajectory
}

TEST(TcnTrainer, EpochsOfOnePassTakeEveryWindowOnce) {
  // Sample weights 1/outputs give every window the total weight 1. With a zero learning rate the
  // parameters never move, so an epoch's training loss is the mean window loss over exactly its
  // windows, and the two epochs of a pass (halves of the set) average to the whole set's loss
  // only if they are disjoint and cover it; epochs of a reshuffled random subset would not.
  TcnDataset data;
  data.sequences.push_back(make_synthetic_friction_sequence(6.0, 400.0, 1));
  TcnTrainOptions o = small_options();
  const TcnTrainer probe(data, o);
  TcnSequence& s = data.sequences[0];
  s.weight = Eigen::MatrixXd::Ones(s.inputs.rows(), 1);
  for (bool held : {false, true})
    for (const TcnTrainer::WindowSpan& w : probe.window_spans(held))
      s.weight.middleRows(w.first_output, w.end - w.first_output)
          .setConstant(1.0 / static_cast<double>(w.end - w.first_output));
  const std::size_t n = probe.training_windows();
  ASSERT_EQ(n % 2, 0u) << "the test needs an even number of training windows";
  o.epoch_windows = static_cast<int>(n / 2);
  o.adam.learning_rate = 0.0;
  o.decay_patience = 0;
  o.patience = 100;
  o.max_epochs = 4;  // two passes
  TcnTrainer trainer(data, o);
  ASSERT_EQ(trainer.training_windows(), n);
  const TcnParameters start = init_tcn_parameters(o.architecture, o.seed);
  const TcnTrainResult result = trainer.train(start);
  const double whole = trainer.loss(start, false);
  ASSERT_EQ(result.history.size(), 4u);
  for (int pass = 0; pass < 2; ++pass) {
    const double first = result.history[2 * pass].train_loss;
    const double second = result.history[2 * pass + 1].train_loss;
    EXPECT_GT(std::abs(first - second), 1e-6 * whole) << "pass " << pass << ": the same windows";
    EXPECT_NEAR(0.5 * (first + second), whole, 1e-12 * whole) << "pass " << pass;
  }
  EXPECT_NE(result.history[0].train_loss, result.history[2].train_loss);  // reshuffled
}

TEST(TcnTrainer, MinLearningRateStopsAtTheDecayBelowItAndChangesNothingBefore) {
  TcnDataset data;
  data.sequences.push_back(make_synthetic_friction_sequence(6.0, 400.0, 1));
  TcnTrainOptions o = small_options();
  o.max_epochs = 60;
  o.decay_patience = 1;  // decays often on this small set
  o.patience = 60;
  o.min_learning_rate = 0.2 * o.adam.learning_rate;  // allows two halvings; the third stops
  const TcnTrainResult stopped = train_tcn(data, o);
  ASSERT_LT(stopped.history.size(), 60u) << "no third decay within 60 epochs";
  EXPECT_TRUE(stopped.stopped_early);
  EXPECT_TRUE(stopped.history.back().last);
  EXPECT_EQ(stopped.history.back().learning_rate, 0.25 * o.adam.learning_rate);
  int decays = 0;
  for (std::size_t e = 1; e < stopped.history.size(); ++e)
    decays += stopped.history[e].learning_rate < stopped.history[e - 1].learning_rate;
  EXPECT_EQ(decays, 2);

  o.min_learning_rate = 0.0;
  o.max_epochs = static_cast<int>(stopped.history.size());
  const TcnTrainResult budget = train_tcn(data, o);
  TcnParameters a = stopped.best, b = budget.best;
  EXPECT_EQ(flatten(a), flatten(b));
  EXPECT_EQ(stopped.best_epoch, budget.best_epoch);
  ASSERT_EQ(stopped.history.size(), budget.history.size());
  for (std::size_t e = 0; e < budget.history.size(); ++e)
    EXPECT_EQ(stopped.history[e].validation_loss, budget.history[e].validation_loss);
}

TEST(TcnTrainer, CheckpointLoadsIntoTheCoreEngineWithTheSameOutputs) {
  TcnDataset data;
  data.sequences.push_back(make_synthetic_friction_sequence(6.0, 400.0, 2));
  TcnTrainOptions o = small_options();
  o.checkpoint_path = (std::filesystem::temp_directory_path() /
                       ("tpf_nn_checkpoint_" + std::to_string(::getpid()) + ".json"))
                          .string();
  int calls = 0;
  const TcnTrainResult result = train_tcn(data, o, [&](const TcnTrainProgress& p) {
    ++calls;
    EXPECT_EQ(p.epoch, calls);
    EXPECT_GE(p.remaining_seconds, 0.0);
  });
  EXPECT_EQ(calls, static_cast<int>(result.history.size()));
  EXPECT_TRUE(result.history.back().last);

  Tcn<double, 4, 8, 3, 4, 1> tcn;
  load_tcn_weights(o.checkpoint_path, tcn);
  std::filesystem::remove(o.checkpoint_path);

  // Stream the raw sequence from a steady start and compare with the trainer's window pass.
  const TcnSequence& s = data.sequences[0];
  const Eigen::Index r = o.architecture.receptive_field();
  Eigen::MatrixXd raw(4, r - 1 + s.inputs.rows());
  raw.leftCols(r - 1).colwise() = s.inputs.row(0).transpose();
  raw.rightCols(s.inputs.rows()) = s.inputs.transpose();
  const Eigen::MatrixXd normalised =
      (raw.colwise() - result.best.input_mean).array().colwise() / result.best.input_std.array();
  TcnWindowWorkspace ws;
  tcn_window_forward(result.best, normalised, ws);
  tcn.reset(s.inputs.row(0).transpose());
  double worst = 0.0;
  for (Eigen::Index t = 0; t < s.inputs.rows(); ++t) {
    tcn.step(s.inputs.row(t).transpose());
    worst = std::max(
        {worst, std::abs(tcn.low()(0) - ws.low(0, t)), std::abs(tcn.high()(0) - ws.high(0, t))});
  }
  EXPECT_LT(worst, 1e-10);
}

TEST(TcnTrainer, HeldOutWindowsAreContiguousBlocksDisjointFromTraining) {
  TcnDataset data;
  data.sequences.push_back(make_synthetic_friction_sequence(20.0, 400.0, 5));  // 8000 samples
  TcnTrainOptions o = small_options();
  o.validation_block_windows = 6;
  o.validation_fraction = 0.25;
  const TcnTrainer trainer(data, o);
  const auto train = trainer.window_spans(false), held = trainer.window_spans(true);
  ASSERT_FALSE(held.empty());
  // No sample (input history or target) of a training window lies in a held-out window.
  for (const auto& t : train)
    for (const auto& h : held)
      EXPECT_TRUE(t.segment != h.segment || t.end <= h.first_input || h.end <= t.first_input)
          << "training [" << t.first_input << ", " << t.end << ") overlaps held-out ["
          << h.first_input << ", " << h.end << ")";
  // Held-out outputs form contiguous stretches of whole blocks: 8000 − 21 outputs in windows of
  // 64 are 125 windows, 21 blocks, round(0.25·21) = 5 held out, so at most 5 stretches.
  int stretches = 0;
  for (std::size_t i = 0; i < held.size(); ++i)
    stretches += i == 0 || held[i].first_output != held[i - 1].end;
  EXPECT_LE(stretches, 5);
  Eigen::Index held_outputs = 0;
  for (const auto& h : held)
    held_outputs += h.end - h.first_output;
  EXPECT_GE(held_outputs, 4 * 6 * 64 - 5 * 21);  // ≈ 5 blocks of 6 windows, less the guards
}

TEST(TcnTrainer, SampleWeightsWeighTheLoss) {
  TcnDataset data;
  data.sequences.push_back(make_synthetic_friction_sequence(6.0, 400.0, 6));
  const TcnTrainOptions o = small_options();
  const TcnParameters p = init_tcn_parameters(o.architecture, 3);
  const double plain = TcnTrainer(data, o).loss(p, false);
  // A uniform weight changes nothing (the MSE is normalised by Σ w).
  data.sequences[0].weight = Eigen::MatrixXd::Constant(data.sequences[0].inputs.rows(), 1, 7.0);
  EXPECT_NEAR(TcnTrainer(data, o).loss(p, false), plain, 1e-6 * plain);  // float windows
  // Weighting half the samples 0 changes it (the per-sample weighting itself is checked against
  // an explicit sum in TcnGradient.SampleScaleWeighsTheLossAndItsGradient).
  TcnDataset masked = data;
  for (Eigen::Index k = 0; k < masked.sequences[0].weight.rows(); k += 2)
    masked.sequences[0].weight(k, 0) = 0.0;
  EXPECT_GT(std::abs(TcnTrainer(masked, o).loss(p, false) - plain), 1e-6 * plain);
  data.sequences[0].weight(10, 0) = -1.0;
  EXPECT_THROW(TcnTrainer(data, o), Error);
}

TEST(TcnTrainer, SkipsNonFiniteRowsAndRefusesBadShapes) {
  TcnDataset data;
  data.sequences.push_back(make_synthetic_friction_sequence(3.0, 400.0, 4));
  data.sequences[0].inputs(500, 2) = std::numeric_limits<double>::quiet_NaN();
  data.sequences[0].residual(700, 0) = std::numeric_limits<double>::infinity();
  TcnTrainer trainer(data, small_options());
  EXPECT_EQ(trainer.skipped_samples(), 2);
  EXPECT_TRUE(trainer.input_mean().allFinite());
  EXPECT_TRUE(
      std::isfinite(trainer.loss(init_tcn_parameters(small_options().architecture, 1), false)));

  data.sequences[0].residual.conservativeResize(Eigen::NoChange, 2);
  try {
    TcnTrainer bad(data, small_options());
    FAIL() << "two residual columns accepted for one output";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("sequences[0].residual"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace tpf::offline
