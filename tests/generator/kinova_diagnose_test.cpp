// diagnose on the measured Kinova Gen3 fitting files (held out by file): a periodic effect is
// judged beside its joint's offset and slope, and claimed only if it also lowers the held-out
// error added to the model alone, as it would be written. On the plain fit (without the inertia
// prior, whose M(q) is not positive definite here) joint 4's motor-angle ripple removes 13 %
// beside an offset and a slope but raises the error by 6.5 % alone: refused, and said. (With the
// prior, diagnose's default, that ripple removes nothing even beside them: no such case.)
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "support/kinova_logs.hpp"
#include "offline/diagnose/diagnose.hpp"
#include "offline/log/read_logs.hpp"

namespace tpf::test {
namespace {

TEST(DiagnoseKinova, ClaimsOnlyWhatLowersTheErrorOfTheModelItWrites) {
  offline::DiagnoseOptions options;
  options.inertia_prior = false;
  const offline::Diagnosis d =
      offline::diagnose(offline::read_logs(kinova_fitting_files()),
                        joint_count_cast<Eigen::Dynamic>(kinova_model()), options);
  for (const offline::Claim& c : d.claims) {
    if (!c.scored_joints.empty()) continue;
    EXPECT_GE(c.improvements[0], options.min_improvement) << d.groups[c.groups[0]].title;
  }
  const auto refused_alone = [](const std::string& f) {
    return f.rfind("Not claimed: motor-angle ripple, joint 4", 0) == 0 &&
           f.find("beside an offset and a slope of its joint") != std::string::npos;
  };
  EXPECT_TRUE(std::any_of(d.findings.begin(), d.findings.end(), refused_alone));
  for (const offline::CandidateTrial& t : d.trials)
    if (t.title.rfind("motor-angle ripple, joint 4", 0) == 0 && t.round == 1) {
      EXPECT_GT(t.improvement, options.min_improvement);
      EXPECT_LT(t.model_improvement, 0.0);
      EXPECT_FALSE(t.selected);
    }
}

}  // namespace
}  // namespace tpf::test
