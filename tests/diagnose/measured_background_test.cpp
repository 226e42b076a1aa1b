// diagnose on measured logs with known effects planted in them: the five multi-joint Kinova Gen3
// files (data/real/kinova-gen3, MIT; 16 s at 1 kHz, held out by file), their current i<j> [mA]
// given an added joint torque τ/K_t. The background is a real arm's (friction with memory,
// unmodelled effects, sensor noise), not a model's. On the unplanted log nothing is claimed; with
// a spring on joint 6, a position ripple of 3 periods in joint 7's range of motion and a
// motor-side ripple (2 periods per motor revolution) on joint 3, each is named on its joint, the
// ripples' frequencies within 3 %, and nothing else is claimed; a ripple of 2 periods in joint 5's
// range is searched within 3 % too.
#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <functional>
#include <set>
#include <string>
#include <vector>

#include "offline/diagnose/diagnose.hpp"
#include "offline/log/read_logs.hpp"
#include "support/claim_names.hpp"
#include "support/kinova_logs.hpp"
#include "tpf/model/joint_count_cast.hpp"

namespace tpf::test {
namespace {

using PlantedModel = Model<double, Eigen::Dynamic>;

const PlantedModel& background_model() {
  static const PlantedModel model = joint_count_cast<Eigen::Dynamic>(kinova_model());
  return model;
}

const offline::Log& background_log() {
  static const offline::Log log = [] {
    std::vector<std::string> files = kinova_fitting_files();
    for (const std::string& f : kinova_testing_files())
      files.push_back(f);
    return offline::read_logs(files);
  }();
  return log;
}

/// The joint torque τ [N·m] a planted effect adds at row k of the log (all joints).
using PlantedTorque = std::function<Eigen::VectorXd(const offline::Log&, Eigen::Index)>;

struct LogColumns {
  std::vector<int> q, dq, i;
};
LogColumns log_columns(const offline::Log& log, int joints) {
  LogColumns c;
  for (int j = 1; j <= joints; ++j) {
    c.q.push_back(log.column(offline::indexed_name("q", j)));
    c.dq.push_back(log.column(offline::indexed_name("dq", j)));
    c.i.push_back(log.column(offline::indexed_name("i", j)));
  }
  return c;
}

/// The log with τ(k) added to its currents (i += 1000·τ/K_t, mA).
offline::Log with_planted(const PlantedTorque& tau) {
  offline::Log log = background_log();
  const PlantedModel& model = background_model();
  const LogColumns c = log_columns(log, model.joint_count());
  for (Eigen::Index k = 0; k < log.rows(); ++k) {
    const Eigen::VectorXd t = tau(background_log(), k);
    for (int j = 0; j < model.joint_count(); ++j)
      log.values(k, c.i[j]) += 1000.0 * t[j] / model.torque_constant[j];
  }
  return log;
}

/// Range of q_j over the log's moving samples [rad].
double moving_range(int j) {
  const offline::Log& log = background_log();
  const LogColumns c = log_columns(log, background_model().joint_count());
  double lo = 1e300, hi = -1e300;
  for (Eigen::Index k = 0; k < log.rows(); ++k)
    if (std::abs(log.values(k, c.dq[j])) > 0.01) {
      lo = std::min(lo, log.values(k, c.q[j]));
      hi = std::max(hi, log.values(k, c.q[j]));
    }
  return hi - lo;
}

offline::Diagnosis planted_diagnosis(const offline::Log& log, const char* label) {
  const offline::Diagnosis d = offline::diagnose(log, background_model());
  std::printf("  [%s] %s\n", label, describe_claims(d).c_str());
  for (const auto& t : d.trials)
    if (t.improvement > 0.05 || t.selected)
      std::printf("    round %d %-62s %6.1f %% transfer %6.1f %%%s\n", t.round, t.title.c_str(),
                  100 * t.improvement, 100 * t.transfer_improvement, t.selected ? " SELECTED" : "");
  for (const auto& f : d.findings)
    std::printf("    %s\n", f.c_str());
  return d;
}

double at(const offline::Log& log, Eigen::Index k, int column) {
  return log.values(k, column);
}

/// The unplanted log's diagnosis, made once per process.
const offline::Diagnosis& unplanted_diagnosis() {
  static const offline::Diagnosis d = planted_diagnosis(background_log(), "unplanted");
  return d;
}

/// Whether the claims name `key` on `joint` (1-based) alone.
bool named_alone(const offline::Diagnosis& d, const std::string& key, int joint) {
  for (const offline::Claim& c : d.claims)
    if (!c.ambiguous() && claim_names(d, c).count(claim_name(key, joint))) return true;
  return false;
}

/// The frequency of the written model's ripple term of `joint` (1-based) on one side [periods
/// per revolution of the joint or of the motor], 0 = none.
double written_cycles(const offline::Diagnosis& d, int joint, bool motor_side) {
  const auto& ripple = d.nominal.added.get<PositionRipple>();
  for (int i = 0; i < ripple.count; ++i)
    if (ripple.terms[i].joint == joint - 1 && ripple.terms[i].motor_side == motor_side)
      return ripple.terms[i].cycles_per_rev;
  return 0.0;
}

/// The output-ripple frequency diagnose tried on `joint` (1-based), read off its candidate's title
/// ("position ripple, joint 5 (3.538 periods/rev of q)"); 0 = none.
double searched_cycles(const offline::Diagnosis& d, int joint) {
  for (const offline::FeatureGroup& g : d.groups)
    if (g.key == "ripple" && g.joint == joint - 1) {
      const std::size_t open = g.title.rfind('(');
      if (open != std::string::npos && std::isdigit(g.title[open + 1]))
        return std::stod(g.title.substr(open + 1));
    }
  return 0.0;
}

TEST(MeasuredBackground, TheUnplantedLogClaimsNothing) {
  EXPECT_TRUE(unplanted_diagnosis().claims.empty()) << describe_claims(unplanted_diagnosis());
}

TEST(MeasuredBackground, PlantedSpringAndRipplesAreNamedOnTheirJoints) {
  const PlantedModel& model = background_model();
  const LogColumns c = log_columns(background_log(), model.joint_count());
  const double ripple_cycles = 3 * 2 * M_PI / moving_range(6);  // 3 periods in joint 7's range
  const double few_cycles = 2 * 2 * M_PI / moving_range(4);     // 2 periods in joint 5's
  const offline::Log log = with_planted([&](const offline::Log& l, Eigen::Index k) {
    Eigen::VectorXd t = Eigen::VectorXd::Zero(model.joint_count());
    t[2] = 2.5 * std::sin(2 * model.gear_ratio[2] * at(l, k, c.q[2]) + 0.7);
    t[4] = 0.8 * std::sin(few_cycles * at(l, k, c.q[4]) + 0.4);
    t[5] = 1.5 * (at(l, k, c.q[5]) - 0.2);
    t[6] = 1.0 * std::sin(ripple_cycles * at(l, k, c.q[6]) + 1.1);
    return t;
  });
  const offline::Diagnosis d = planted_diagnosis(log, "motor ripple j3, spring j6, ripple j7");
  std::printf("  planted: %.3f periods/rev on joint 7, %.3f on joint 5\n", ripple_cycles,
              few_cycles);
  // Joint 5's ripple, 2 periods in view, is searched within 3 % (3.538/rev; the declared fit
  // alone absorbs part of it and shows 3.886) but does not transfer to RecordTrajectory_quadratic
  // held out (+16.9 %): not claimed, and nothing in its place.
  EXPECT_NEAR(searched_cycles(d, 5), few_cycles, 0.03 * few_cycles);
  EXPECT_TRUE(named_alone(d, "spring", 6)) << describe_claims(d);
  EXPECT_TRUE(named_alone(d, "ripple", 7)) << describe_claims(d);
  EXPECT_TRUE(named_alone(d, "ripple_motor", 3)) << describe_claims(d);
  EXPECT_EQ(d.claims.size(), unplanted_diagnosis().claims.size() + 3) << describe_claims(d);
  EXPECT_NEAR(written_cycles(d, 7, false), ripple_cycles, 0.03 * ripple_cycles);
  EXPECT_NEAR(written_cycles(d, 3, true), 2.0, 0.06);
  for (const offline::Claim& claim : d.claims)
    if (d.groups[claim.groups[0]].key == "spring") {
      EXPECT_NEAR(claim.coefficients[0], 1.5, 0.15);  // k6, N·m/rad
    }
}

}  // namespace
}  // namespace tpf::test
