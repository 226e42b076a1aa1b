// The inertia prior on the measured Kinova Gen3 (held out by file): its 8.8 s of fitting files do
// not excite every inertia, so the plain fit's M(q) is not positive definite; pulled toward the
// robot file's inertias just enough, identify's model is physical and predicts the two scoring
// files' effort better (every joint measured ≈ 4–48 % lower RMS). diagnose's:
// cli_inertia_prior_test.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "kinova_logs.hpp"
#include "offline/identify/identify.hpp"
#include "offline/identify/joint_samples.hpp"
#include "offline/log/read_logs.hpp"

namespace tpf::test {
namespace {

/// RMS per joint [N·m] of effort − model on the scoring files' valid samples.
Eigen::VectorXd scoring_rms(const NominalModel<double, 7>& nominal) {
  const offline::Log log = offline::read_logs(kinova_testing_files());
  offline::SampleOptions options;
  options.hold_out = false;
  const offline::JointSamples s =
      offline::extract_joint_samples(log, nominal.model.torque_constant, options);
  const Eigen::MatrixXd residual = offline::nominal_residual<7>(nominal, s);
  Eigen::VectorXd sum = Eigen::VectorXd::Zero(7), count = sum;
  for (Eigen::Index k = 0; k < s.size(); ++k)
    for (int j = 0; j < 7; ++j)
      if (std::isfinite(residual(k, j))) sum[j] += residual(k, j) * residual(k, j), ++count[j];
  return (sum.array() / count.array()).sqrt();
}

TEST(InertiaPriorKinova, MakesTheMassMatrixPhysicalAndPredictsTheHeldOutFilesBetter) {
  const offline::Log fit = offline::read_logs(kinova_fitting_files());
  offline::IdentifyOptions options;
  EXPECT_TRUE(options.inertia_prior);  // the default
  const auto with = offline::identify<7>(fit, kinova_model(), options);
  options.inertia_prior = false;
  const auto plain = offline::identify<7>(fit, kinova_model(), options);
  EXPECT_LT(plain.consistency.min_mass_eigenvalue, -1.0);  // measured −2.07 kg·m²
  // The plain fit's check points at the prior; with it the model passes the check.
  const auto points_at_prior = [](const std::string& problem) {
    return problem.find("without --no-inertia-prior") != std::string::npos;
  };
  EXPECT_TRUE(std::any_of(plain.consistency.problems.begin(), plain.consistency.problems.end(),
                          points_at_prior));
  EXPECT_TRUE(with.consistency.consistent());
  EXPECT_EQ(with.inertia_prior.written_min_eigenvalue, plain.consistency.min_mass_eigenvalue);
  EXPECT_GT(with.inertia_prior.written_strength, 0.0);
  EXPECT_LT(with.inertia_prior.written_strength, 1.0);  // measured 0.19: the data still lead
  // A tenth of the robot file's own smallest eigenvalue (0.040 kg·m²), reached from below.
  EXPECT_GT(with.consistency.min_mass_eigenvalue, 0.004);
  EXPECT_LT(with.consistency.min_mass_eigenvalue, 0.0045);
  const Eigen::VectorXd before = scoring_rms(plain.nominal), after = scoring_rms(with.nominal);
  int lower = 0;
  for (int j = 0; j < 7; ++j) {
    std::printf("[ measured ] joint %d: held-out effort RMS %.3f -> %.3f N·m\n", j + 1, before[j],
                after[j]);
    lower += after[j] < before[j];
  }
  EXPECT_GE(lower, 6);
  EXPECT_LT(after.squaredNorm(), 0.6 * before.squaredNorm());  // measured 0.49
}

}  // namespace
}  // namespace tpf::test
