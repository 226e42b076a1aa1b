// No weaker stand-in for a candidate that failed the transfer test. One joint, on Gram matrices
// built from seeded rows: the residual holds an effect e = u₁ + 0.8·u₂ in every file, which no
// single candidate names exactly. Candidate "wide" (u₁, u₂ and a column w that is small in the
// fitting files and 10⁵ times larger in another) explains all of it on the selection's
// held-out rows but fails on that other file; candidate "proxy" (u₁ alone) explains part of it
// there and transfers. "proxy" beside "wide" explains nothing more: it stands in for the failed
// explanation of the same residual, so nothing is claimed and the findings say so. Without "wide"
// in the library the same "proxy" is claimed (the rule, not the data, refuses it).
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <string>
#include <vector>

#include "offline/diagnose/diagnosis_findings.hpp"
#include "offline/diagnose/effect_selection.hpp"

namespace tpf::test {
namespace {

using offline::DesignGrams;
using offline::FeatureGroup;

// Columns: 0 declared (x), 1–2 u₁ u₂, 3 w, 4 proxy (a copy of u₁).
constexpr int kFeatures = 5;
constexpr int kMoving = 2;  // regime index of DesignGrams

/// Rows of one file: y = x + u₁ + 0.8·u₂ + noise, w of scale `w_scale`.
void add_file(DesignGrams& g, int split, double w_scale, std::mt19937_64& rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  for (int k = 0; k < 400; ++k) {
    const double x = normal(rng), u1 = normal(rng), u2 = normal(rng);
    const double w = w_scale * normal(rng);
    const double y = x + u1 + 0.8 * u2 + 0.3 * normal(rng);
    Eigen::VectorXd z(kFeatures + 2);
    z << x, u1, u2, w, u1, y, 1.0;
    g.at(0, kMoving, split) += z * z.transpose();
  }
}

struct Library {
  DesignGrams selection{1, kFeatures};
  offline::TransferFold transfer{"other.csv", DesignGrams(1, kFeatures)};
  std::vector<FeatureGroup> groups;
};

/// The selection: fitted on two files, held out on a third, all with w small; the transfer fold:
/// the same fitting files, held out on a file whose w is 10⁵ times larger.
Library library(bool with_wide) {
  Library l;
  std::mt19937_64 rng(7);
  for (DesignGrams* g : {&l.selection, &l.transfer.grams}) {
    std::mt19937_64 same(3);
    add_file(*g, 0, 0.001, same);
    add_file(*g, 0, 0.001, same);
  }
  add_file(l.selection, 1, 0.001, rng);
  add_file(l.transfer.grams, 1, 100.0, rng);
  FeatureGroup declared;
  declared.key = "rigid";
  declared.title = "declared";
  declared.joint = 0;
  declared.declared = true;
  declared.columns = {0};
  l.groups.push_back(declared);
  if (with_wide) {
    FeatureGroup wide;
    wide.key = "coupling";
    wide.title = "wide, joint 1";
    wide.joint = 0;
    wide.columns = {1, 2, 3};
    l.groups.push_back(wide);
  }
  FeatureGroup proxy;
  proxy.key = "load_friction";
  proxy.title = "proxy, joint 1";
  proxy.joint = 0;
  proxy.columns = {4};
  l.groups.push_back(proxy);
  return l;
}

offline::EffectSelection run_selection(const Library& l, const offline::DiagnoseOptions& options) {
  offline::FitSelection fit;
  fit.regimes = {false, false, true};
  fit.joint_weights = Eigen::VectorXd::Ones(1);
  offline::FitSelection every = fit;
  every.heldout_rows = true;
  const std::vector<int> declared{0};
  const Eigen::VectorXd theta = offline::fit_columns(l.selection, declared, fit);
  return offline::select_effects(l.selection, {l.transfer}, {}, l.groups, declared, theta, fit,
                                 every, Eigen::VectorXd::Ones(1), options);
}

const offline::CandidateTrial& trial(const offline::EffectSelection& s, const std::string& title) {
  return *std::find_if(s.trials.begin(), s.trials.end(),
                       [&](const offline::CandidateTrial& t) { return t.title == title; });
}

TEST(StandIn, AWeakerCandidateIsNotClaimedForTheResidualOfOneThatFailedTransfer) {
  const offline::DiagnoseOptions options;
  const Library l = library(true);
  const offline::EffectSelection s = run_selection(l, options);
  const offline::CandidateTrial& wide = trial(s, "wide, joint 1");
  const offline::CandidateTrial& proxy = trial(s, "proxy, joint 1");
  // The wide candidate explains the whole effect here and fails on the other file …
  EXPECT_GT(wide.improvement, 0.8);
  EXPECT_TRUE(wide.fails_transfer(options));
  // … the proxy explains u₁'s share (1/1.64 of the effect's energy) and transfers …
  EXPECT_NEAR(proxy.improvement, 1.0 / 1.64, 0.08);
  EXPECT_GT(proxy.transfer_improvement, options.min_improvement);
  EXPECT_FALSE(proxy.fails_transfer(options));
  // … but beside the wide one it adds nothing: it stands in for it, and is not claimed.
  EXPECT_TRUE(proxy.stands_in(options));
  EXPECT_EQ(proxy.stand_in_for, "wide, joint 1");
  EXPECT_LT(proxy.beside_failed_improvement, 0.01);
  EXPECT_TRUE(s.claims.empty());

  offline::EffectDiagnosis d;
  d.groups = l.groups;
  d.trials = s.trials;
  const std::vector<std::string> findings = offline::diagnosis_findings(d, options);
  const auto says = [&](const std::string& a, const std::string& b) {
    return std::any_of(findings.begin(), findings.end(), [&](const std::string& f) {
      return f.find(a) != std::string::npos && f.find(b) != std::string::npos;
    });
  };
  EXPECT_TRUE(says("Not claimed: wide, joint 1", "does not transfer between files"));
  EXPECT_TRUE(says("Not claimed: proxy, joint 1", "beside wide, joint 1"));
}

TEST(StandIn, TheSameCandidateIsClaimedWhenNoStrongerOneFailed) {
  const offline::DiagnoseOptions options;
  const offline::EffectSelection s = run_selection(library(false), options);
  ASSERT_EQ(s.claims.size(), 1u);
  EXPECT_EQ(s.claims[0].groups, std::vector<int>{1});
  EXPECT_NEAR(s.claims[0].coefficients[0], 1.0, 0.1);  // u₁'s coefficient
  EXPECT_FALSE(trial(s, "proxy, joint 1").stands_in(options));
}

}  // namespace
}  // namespace tpf::test
