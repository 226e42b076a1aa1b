// The compensator without an input (tpf train --without-input) on logs the twin did not make
// (planar_arm_generator): the written networks must not depend on the masked input at all.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "offline/compensator_training/tcn_parameters.hpp"
#include "offline/compensator_training/train_compensator.hpp"
#include "offline/replay/estimator_samples.hpp"
#include "offline/replay/replay_estimator.hpp"
#include "planar_arm_generator.hpp"
#include "tpf/common/error.hpp"
#include "tpf/estimation/compensator_types.hpp"
#include "tpf/model/load_robot.hpp"
#include "tpf/nn/load_tcn_weights.hpp"
#include "tpf/nn/per_joint_tcn_compensator.hpp"

namespace tpf::test {
namespace {

using MaskedPlanarCompensator =
    PerJointTcnCompensator<double, 2, offline::kPerJointHiddenSmall, kCompensatorLevels>;

// The estimator's trace over a 60 s generator log (default estimator parameters; rigid body not
// identified: the networks learn the whole effort, which depends strongly on q through gravity).
const offline::EstimatorTrace& planar_trace() {
  static const offline::EstimatorTrace trace = [] {
    PlanarArmPlant plant;
    plant.seed = 5;
    plant.duration_s = 60.0;
    const offline::Log log = generate_planar_log(plant);
    EstimatorSetup<2> planar;
    planar.nominal.model = load_robot<double, 2>(planar_robot_file());
    const offline::ReplaySetup setup = joint_count_cast<Eigen::Dynamic>(planar);
    return offline::replay_estimator(setup,
                                     offline::estimator_samples(log, setup.nominal.model, 0));
  }();
  return trace;
}

offline::CompensatorTraining train_planar(const std::vector<int>& masked, int threads = 1) {
  offline::CompensatorTrainingOptions o;
  o.per_joint = true;
  o.masked_inputs = masked;
  o.tcn.max_epochs = 2;
  o.tcn.threads = threads;
  o.tcn.validation_block_windows = 2;
  return offline::train_compensator({planar_trace()}, o);
}

// Streams the trace's inputs with q_j replaced by `q_shift` + 3·q_j through networks loaded from
// the written files; returns the outputs (rows × 2).
Eigen::MatrixXd stream(const offline::CompensatorTraining& training, double q_shift,
                       const std::string& stem) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("tpf-mask-" + std::to_string(::getpid()) + "-" + stem);
  const auto paths = offline::write_compensator(training, dir / "planar.tcn.json");
  auto compensator = std::make_unique<MaskedPlanarCompensator>();
  for (int j = 0; j < 2; ++j)
    load_tcn_weights(paths[static_cast<std::size_t>(j)], compensator->network(j));
  std::filesystem::remove_all(dir);
  const offline::EstimatorTrace& trace = planar_trace();
  Eigen::MatrixXd out(trace.rows(), 2);
  for (Eigen::Index k = 0; k < trace.rows(); ++k) {
    CompensatorInput<double, 2> x = trace.inputs.row(k).transpose();
    for (int j = 0; j < 2; ++j)
      x[j] = q_shift + 3.0 * x[j];  // channel 0 (q) of joint j is x_j
    if (k == 0) compensator->reset(x);
    out.row(k) = compensator->step(x).transpose();
  }
  return out;
}

TEST(CompensatorWithoutPosition, OutputDoesNotDependOnQAtAll) {
  const offline::CompensatorTraining masked = train_planar({offline::kPositionInput});
  ASSERT_EQ(masked.files.size(), 2u);
  for (const TcnWeightFile& f : masked.files) {
    EXPECT_EQ(f.input_mean[0], 0.0);
    EXPECT_EQ(f.input_std[0], 1.0);
    const TcnTensor& conv = f.tensors.at(tcn_conv_weight_name(0));  // [H, In, K]
    const TcnTensor& skip = f.tensors.at(tcn_downsample_name());    // [H, In, 1]
    for (int h = 0; h < f.hidden; ++h) {
      for (int k = 0; k < f.kernel; ++k)
        EXPECT_EQ(conv.values[static_cast<std::size_t>((h * f.inputs) * f.kernel + k)], 0.0);
      EXPECT_EQ(skip.values[static_cast<std::size_t>(h * f.inputs)], 0.0);
    }
  }
  const Eigen::MatrixXd a = stream(masked, 0.0, "a"), b = stream(masked, 1.7, "b");
  ASSERT_TRUE(a.allFinite());
  EXPECT_EQ((a - b).cwiseAbs().maxCoeff(), 0.0) << "a network without q must ignore q exactly";
  EXPECT_GT(a.cwiseAbs().maxCoeff(), 1e-6) << "the masked networks still predict something";

  // The same training with q seen: its output moves with q, so the check above can fail.
  const offline::CompensatorTraining full = train_planar({});
  const Eigen::MatrixXd c = stream(full, 0.0, "c"), d = stream(full, 1.7, "d");
  EXPECT_GT((c - d).cwiseAbs().maxCoeff(), 1e-3);
}

TEST(CompensatorTraining, NetworksTrainedAtOnceOnTwoThreadsAreTheSame) {
  const offline::CompensatorTraining one = train_planar({}, 1);
  const offline::CompensatorTraining two = train_planar({}, 2);  // one network per thread
  ASSERT_EQ(one.results.size(), 2u);
  ASSERT_EQ(two.results.size(), 2u);
  for (std::size_t j = 0; j < 2; ++j) {
    EXPECT_EQ(one.results[j].best_validation_loss, two.results[j].best_validation_loss);
    offline::TcnParameters serial = one.results[j].best, concurrent = two.results[j].best;
    EXPECT_EQ(offline::flatten(serial), offline::flatten(concurrent));
  }
}

TEST(CompensatorWithoutPosition, InputNamesMapToChannelsAndUnknownNamesAreRefused) {
  EXPECT_EQ(offline::compensator_input_channel("q"), offline::kPositionInput);
  EXPECT_EQ(offline::compensator_input_channel("static-friction"), offline::kStaticFrictionInput);
  EXPECT_EQ(offline::compensator_input_channel("nominal-friction"), 4);
  EXPECT_THROW(offline::compensator_input_channel("position"), Error);
}

}  // namespace
}  // namespace tpf::test
