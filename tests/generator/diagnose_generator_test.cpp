// Diagnosis on logs the twin did not make (planar_arm_generator): each library effect and each
// trap of a confident wrong name planted on a two-link planar arm with friction memory, noise,
// quantisation and random stops. Asserts the right name on the right joint, or "ambiguous"
// naming it, and never a claim that names something else; nothing on a clean log.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "offline/diagnose/diagnose.hpp"
#include "offline/effects/effect_columns.hpp"
#include "offline/log/log_writer.hpp"
#include "offline/log/read_logs.hpp"
#include "planar_arm_generator.hpp"
#include "support/claim_names.hpp"
#include "tpf/dynamics/rnea.hpp"
#include "tpf/estimation/nominal_model.hpp"
#include "tpf/model/inertia.hpp"
#include "tpf/model/load_robot.hpp"

namespace tpf::test {
namespace {

using offline::Diagnosis;
using V2 = JointVector<double, 2>;

const Model<double, 2>& planar_model() {
  static const Model<double, 2> model = load_robot<double, 2>(planar_robot_file());
  return model;
}

/// The same arm at the tools' run-time joint count.
const Model<double, Eigen::Dynamic>& planar_model_x() {
  static const Model<double, Eigen::Dynamic> model =
      load_robot<double, Eigen::Dynamic>(planar_robot_file());
  return model;
}

Diagnosis run(const PlanarArmPlant& plant, const char* label) {
  const offline::Log log = generate_planar_log(plant);
  auto d = offline::diagnose(log, planar_model_x());
  std::printf("  [%s] %s\n", label, describe_claims(d).c_str());
  for (const auto& t : d.trials)
    if (t.improvement > 0.03 || t.selected || std::getenv("TPF_GENERATOR_TRIALS"))
      std::printf("    round %d %-62s %6.1f %% BIC %8.0f %5.1f SE share %.3f%s\n", t.round,
                  t.title.c_str(), 100 * t.improvement, t.bic_change, t.wald, t.distinct_share,
                  t.selected ? " SELECTED" : "");
  for (const auto& f : d.findings)
    std::printf("    %s\n", f.c_str());
  const offline::CadPayloadCheck& c = d.cad_payload;
  std::printf("    CAD payload check: %s, %.3f ± %.3f kg, %.1f %% beside the selected effects\n",
              c.claimed       ? "claimed"
              : c.ambiguous() ? "ambiguous"
                              : "not claimed",
              c.mass, c.mass_standard_error, 100 * c.improvement);
  // What a claim prints is the gain of what it writes: added to the model as it stands (not
  // beside its joint's offset and slope, which a periodic effect is also judged against).
  for (const offline::Claim& claim : d.claims) {
    if (!claim.scored_joints.empty()) continue;
    EXPECT_GE(claim.improvements[0], offline::DiagnoseOptions{}.min_improvement)
        << label << ": " << d.groups[claim.groups[0]].title;
  }
  return d;
}

// The planted effect `key` (on `joint`, 1-based; 0 = every joint, a global claim) is named or
// is one of an ambiguous claim's names; every claim names only something in `allowed`.
enum class Outcome { Named, Ambiguous, Missed };
Outcome outcome(const Diagnosis& d, const std::string& key, int joint) {
  Outcome best = Outcome::Missed;
  for (const offline::Claim& c : d.claims) {
    const auto names = claim_names(d, c);
    bool hit = names.count(key + "@" + std::to_string(joint)) > 0;
    if (joint == 0) hit = hit || names.count(key + "@0") > 0;
    if (hit) best = c.ambiguous() ? std::min(best, Outcome::Ambiguous) : Outcome::Named;
  }
  return best;
}

void expect_only(const Diagnosis& d, const std::set<std::string>& allowed) {
  for (const offline::Claim& c : d.claims)
    for (const std::string& name : claim_names(d, c)) {
      const std::string key = name.substr(0, name.find('@'));
      if (c.ambiguous()) {
        // An ambiguous claim may list a candidate that is not planted, but must list one that is.
        bool any = false;
        for (const std::string& n : claim_names(d, c))
          any = any || allowed.count(n) || allowed.count(n.substr(0, n.find('@')));
        EXPECT_TRUE(any) << describe_claims(d);
      } else {
        EXPECT_TRUE(allowed.count(name) || allowed.count(key))
            << "confident wrong name " << name << ": " << describe_claims(d);
      }
    }
}

// The CAD check claims no payload the generator did not plant: no claim, or "ambiguous between
// the payload and" a selected effect that is one of `planted`.
void expect_no_unplanted_payload(const Diagnosis& d, const std::set<std::string>& planted) {
  const offline::CadPayloadCheck& c = d.cad_payload;
  EXPECT_FALSE(c.claimed) << "payload " << c.mass << " ± " << c.mass_standard_error << " kg, "
                          << 100 * c.improvement << " % beyond the selected effects";
  for (int g : c.ambiguous_with) {
    const std::string name = d.groups[g].key + "@" + std::to_string(d.groups[g].joint + 1);
    EXPECT_TRUE(planted.count(name) || planted.count(d.groups[g].key))
        << "payload ambiguous with " << name << ", not planted";
  }
}

NominalModelX through_a_file(const NominalModelX& model) {
  const auto path = std::filesystem::temp_directory_path() /
                    ("tpf_generator_params_" + std::to_string(::getpid()) + ".json");
  save_nominal_model(path, model, "generator");
  const NominalModelX loaded = load_nominal_model(path, planar_robot_file());
  std::filesystem::remove(path);
  return loaded;
}

double largest_difference(const offline::JointSamples& s, const Eigen::MatrixXd& a,
                          const Eigen::MatrixXd& b) {
  double worst = 0;
  for (Eigen::Index k = 0; k < s.size(); ++k)
    if (s.valid[k]) worst = std::max(worst, (a.row(k) - b.row(k)).cwiseAbs().maxCoeff());
  return worst;
}

// What diagnose adds is what runs: the model it judged (fitted on the training rows), through a
// parameter file into the run-time NominalModel, predicts what diagnose predicted (1e-9), and
// each written effect's run-time term (prediction with it minus without it) equals the term
// diagnose fitted (its columns × θ) on the moving samples (where the regressor's sgn, by
// threshold, and the run time's agree). The file it writes holds that model refitted on every
// row: the same effects, its own round trip to 1e-9.
void expect_written_model_runs(const Diagnosis& d) {
  const offline::JointSamples& s = d.samples;
  const NominalModelX loaded = through_a_file(d.judged);
  EXPECT_LT(largest_difference(s, offline::nominal_residual(loaded, s), d.residual_written), 1e-9);
  EXPECT_LT(largest_difference(s, offline::nominal_residual(through_a_file(d.nominal), s),
                               offline::nominal_residual(d.nominal, s)),
            1e-9);
  EXPECT_TRUE(d.refitted) << "the generator's log holds blocks out";
  int checked = 0;
  for (std::size_t e = 0; e < d.selected.size(); ++e) {
    if (!d.claims[e].written) continue;
    const offline::FeatureGroup& g = d.groups[d.selected[e]];
    // Not a term of its own in the written model: a payload is folded into the base parameters,
    // load-dependent friction refitted with the Stribeck curves.
    if (g.written_to == offline::WrittenTo::kRigidBody || g.key == "load_friction") continue;
    NominalModelX without = loaded;
    offline::remove_group(g, without);
    const int j = g.joint;
    ++checked;
    Data<double, Eigen::Dynamic> data(loaded.model);
    double term_error = 0;
    for (Eigen::Index k = 0; k < s.size(); k += 7) {
      if (!s.valid[k] || std::abs(s.dq(k, j)) < 1e-4) continue;
      const Eigen::VectorXd q = s.q.row(k).transpose(), dq = s.dq.row(k).transpose(),
                            ddq = s.ddq.row(k).transpose();
      Eigen::VectorXd r1, f1, r0, f0;
      predict_effort(loaded, data, q, dq, ddq, r1, f1);
      predict_effort(without, data, q, dq, ddq, r0, f0);
      term_error = std::max(term_error, std::abs((r1 + f1 - r0 - f0)[j] - d.effect_terms[e](k, j)));
    }
    EXPECT_LT(term_error, 1e-9) << g.title;
  }
  EXPECT_GT(checked, 0);
}

TEST(Generator, ClosedFormDynamicsAgreeWithTheRobotFile) {
  // The generator's own dynamics (Lagrange, closed form) and tpf's RNEA on planar2.urdf: the
  // same arm, so diagnosis is judged against physics, not against a shared bug.
  const PlanarArm arm;
  Data<double, 2> data;
  for (const auto& [q, dq, ddq] : {std::tuple{V2(0.3, -1.1), V2(0.7, -0.4), V2(2.0, 1.5)},
                                   std::tuple{V2(-2.0, 0.5), V2(-1.3, 2.1), V2(-0.5, 3.0)}}) {
    const V2 expected = arm.inverse_dynamics(q, dq, ddq);
    const V2 tau = rnea(planar_model(), data, q, dq, ddq);
    EXPECT_NEAR(tau[0], expected[0], 1e-9);
    EXPECT_NEAR(tau[1], expected[1], 1e-9);
  }
}

TEST(Generator, ClosedFormDynamicsWithAPayloadAgreeWithTheRobotFilePlusThePayload) {
  // The payload the generator plants (a point mass in the forearm's frame) is the one the CAD
  // check looks for: the robot file's last link plus that body, through RNEA.
  PlanarArm arm;
  arm.payload_mass = 0.5;
  arm.payload_com = {0.25, 0.04};
  Model<double, 2> model = planar_model();
  Inertia<double> payload;
  payload.mass = 0.5;
  payload.com = Vector3<double>(0.25, 0.0, 0.04);
  model.inertias[2] =
      Inertia<double>::from_parameters(model.inertias[2].parameters() + payload.parameters());
  model.update_constants();
  Data<double, 2> data;
  for (const auto& [q, dq, ddq] : {std::tuple{V2(0.3, -1.1), V2(0.7, -0.4), V2(2.0, 1.5)},
                                   std::tuple{V2(-2.0, 0.5), V2(-1.3, 2.1), V2(-0.5, 3.0)}}) {
    const V2 expected = arm.inverse_dynamics(q, dq, ddq);
    const V2 tau = rnea(model, data, q, dq, ddq);
    EXPECT_NEAR(tau[0], expected[0], 1e-9);
    EXPECT_NEAR(tau[1], expected[1], 1e-9);
  }
}

TEST(Generator, CleanLogClaimsNothing) {
  for (std::uint64_t seed : {11u, 12u}) {
    PlanarArmPlant plant;
    plant.seed = seed;
    const auto d = run(plant, "clean");
    EXPECT_TRUE(d.claims.empty()) << describe_claims(d);
    // Nor a payload against the robot file's inertias (the robot file is the generator's arm).
    EXPECT_FALSE(d.cad_payload.claimed) << d.cad_payload.mass << " kg";
  }
}

TEST(Generator, ALogShorterThanTheFirstHeldOutBlockSaysSoInsteadOfNoGain) {
  // One file of 10 s: the interleaved split holds out nothing (the first held-out block starts at
  // 15 s). Nothing is claimed, and the finding says that nothing is held out, not that no
  // candidate lowers the held-out residual.
  PlanarArmPlant plant;
  plant.seed = 11;
  plant.duration_s = 10.0;
  plant.offset = {0.0, 0.3};
  const auto d = run(plant, "10 s, nothing held out");
  EXPECT_TRUE(d.claims.empty()) << describe_claims(d);
  bool said = false;
  for (const auto& f : d.findings) {
    said = said || f.find("nothing is held out") != std::string::npos;
    EXPECT_EQ(f.find("none lowers the held-out residual"), std::string::npos) << f;
  }
  EXPECT_TRUE(said);
}

TEST(Generator, OffsetUnderAShortRangeIsNeverARipple) {
  PlanarArmPlant plant;
  plant.seed = 21;
  plant.amplitude = {1.2, 0.2};  // joint 2 moves over 0.4 rad: no ripple period fits
  plant.offset = {0.0, 0.3};
  const auto d = run(plant, "offset, short range");
  EXPECT_NE(outcome(d, "offset", 2), Outcome::Missed) << describe_claims(d);
  expect_only(d, {"offset@2", "asymmetric_friction@2"});
  // A payload's gravity on the forearm is nearly constant over 0.4 rad of q2: without the selected
  // offset beside it, the CAD check took 0.093 kg for the offset (−79.6 %).
  expect_no_unplanted_payload(d, {"offset@2", "asymmetric_friction@2"});
}

TEST(Generator, AsymmetricCoulombIsNotASpring) {
  PlanarArmPlant plant;
  plant.seed = 22;
  plant.coulomb_positive = {0.60, 0.25};
  plant.coulomb_negative = {0.25, 0.25};
  const auto d = run(plant, "asymmetric Coulomb");
  EXPECT_NE(outcome(d, "asymmetric_friction", 1), Outcome::Missed) << describe_claims(d);
  expect_only(d, {"asymmetric_friction@1", "offset@1"});
}

TEST(Generator, DelayOnEveryJointIsOneDelay) {
  PlanarArmPlant plant;
  plant.seed = 23;
  plant.delay_s = 0.02;
  const auto d = run(plant, "delay 20 ms, all joints");
  EXPECT_EQ(outcome(d, "delay", 0), Outcome::Named) << describe_claims(d);
  expect_only(d, {"delay"});
  for (const offline::Claim& c : d.claims)
    if (!c.ambiguous() && d.groups[c.groups[0]].joint == -1) {
      EXPECT_NEAR(c.coefficients[0], -0.02, 0.005);  // the effort lags: a negative lead, s
    }
}

TEST(Generator, FrictionGrowingWithTheNeighboursLoad) {
  PlanarArmPlant plant;
  plant.seed = 24;
  plant.neighbour_load = 0.25;  // joint 1's level grows by 0.25·|G_2| (up to 0.43 N·m)
  const auto d = run(plant, "neighbour-load friction");
  EXPECT_EQ(outcome(d, "neighbour_load_friction", 1), Outcome::Named) << describe_claims(d);
  expect_only(d, {"neighbour_load_friction@1"});
  for (const offline::Claim& c : d.claims)
    if (d.groups[c.groups[0]].key == "neighbour_load_friction") {
      EXPECT_NEAR(c.coefficients[0], 0.25, 0.08);  // β_c of |G_2| on joint 1's level
    }
  expect_written_model_runs(d);
}

TEST(Generator, SpringBesideGravityIsNotClaimedConfidently) {
  PlanarArmPlant plant;
  plant.seed = 25;
  plant.amplitude = {0.05, 0.3};  // the forearm's gravity is nearly linear in q2 over the range
  plant.spring_stiffness = {0.0, 3.0};
  plant.spring_neutral = {0.0, 0.2};
  const auto d = run(plant, "spring beside gravity");
  for (const offline::Claim& c : d.claims) {
    if (d.groups[c.groups[0]].key == "spring") {
      EXPECT_TRUE(c.ambiguous()) << describe_claims(d);
    }
  }
  expect_only(d, {"spring@2", "offset@2"});
  // … nor as a payload (its gravity is nearly linear in q2 over the range: 0.251 kg, −78.8 %,
  // when the CAD check was not judged beside the selected spring).
  expect_no_unplanted_payload(d, {"spring@2", "offset@2"});
}

TEST(Generator, RippleAndSpringOverAWideRange) {
  // The spring acts on the forearm, whose gravity depends on q1 + q2: over the wide motion of
  // both joints, k·q2 is not a combination of the gravity columns. (On joint 1 the identified
  // gravity absorbs a spring: sin q1 is nearly linear over the range, the trap of the test above.)
  PlanarArmPlant plant;
  plant.seed = 26;
  plant.amplitude = {1.2, 1.5};
  plant.ripple_amplitude = {0.12, 0.0};
  plant.ripple_cycles = {8, 8};
  plant.spring_stiffness = {0.0, 1.5};
  plant.spring_neutral = {0.0, 0.3};
  const auto d = run(plant, "ripple j1, spring j2");
  EXPECT_EQ(outcome(d, "ripple", 1), Outcome::Named) << describe_claims(d);
  EXPECT_NE(outcome(d, "spring", 2), Outcome::Missed) << describe_claims(d);
  expect_only(d, {"ripple@1", "spring@2", "offset@2"});
  expect_written_model_runs(d);
}

/// The frequency of the written model's ripple term of `joint` (1-based) on one side, 0 = none.
double written_ripple_cycles(const Diagnosis& d, int joint, bool motor_side) {
  const auto& ripple = d.nominal.added.get<PositionRipple>();
  for (int i = 0; i < ripple.count; ++i)
    if (ripple.terms[i].joint == joint - 1 && ripple.terms[i].motor_side == motor_side)
      return ripple.terms[i].cycles_per_rev;
  return 0.0;
}

TEST(Generator, RippleFrequencyIsARealNumber) {
  // 30.65 periods/rev on joint 1 (a gear's meshing ratio), 11.7 periods over its 2.4 rad of
  // motion: named and written at its fitted frequency, not at the integer 31.
  PlanarArmPlant plant;
  plant.seed = 27;
  plant.ripple_amplitude = {0.12, 0.0};
  plant.ripple_cycles = {30.65, 8};
  const auto d = run(plant, "ripple 30.65/rev j1");
  EXPECT_EQ(outcome(d, "ripple", 1), Outcome::Named) << describe_claims(d);
  expect_only(d, {"ripple@1"});
  const double f = written_ripple_cycles(d, 1, false);
  std::printf("    written: %.4f periods/rev (planted 30.65)\n", f);
  EXPECT_LT(std::abs(f - 30.65) / 30.65, 0.03) << f;
  EXPECT_NEAR(f, 30.65, 0.15);
  expect_written_model_runs(d);
}

TEST(Generator, RippleUnderOnePeriodNamesNoFrequency) {
  // Joint 2 moves over 0.4 rad, where a ripple of 12 periods/rev shows 0.76 of a period: that
  // stretch of sine explains the residual, but its frequency could be anything near it and it is
  // an offset and a spring as well. Claimed as ambiguous with them, named with no frequency, and
  // not written. (240 s: on 60 s its coefficients are within 2 standard errors of zero.)
  PlanarArmPlant plant;
  plant.seed = 28;
  plant.duration_s = 240;
  plant.amplitude = {1.2, 0.2};
  plant.ripple_amplitude = {0.0, 1.0};
  plant.ripple_cycles = {8, 12};
  const auto d = run(plant, "ripple 12/rev j2 over 0.4 rad");
  EXPECT_EQ(outcome(d, "ripple", 2), Outcome::Ambiguous) << describe_claims(d);
  for (const offline::Claim& c : d.claims)
    if (d.groups[c.groups[0]].key == "ripple") {
      const auto names = claim_names(d, c);
      EXPECT_TRUE(names.count("offset@2") && names.count("spring@2")) << describe_claims(d);
    }
  for (const offline::FeatureGroup& g : d.groups)
    if (g.key == "ripple" && g.joint == 1) {
      EXPECT_TRUE(g.indistinct_from_beside) << g.title;
      EXPECT_EQ(g.title.find("periods/rev"), std::string::npos) << g.title;
    }
  EXPECT_EQ(written_ripple_cycles(d, 2, false), 0.0);
  expect_only(d, {"offset@2", "spring@2", "ripple@2"});
}

// Files of the generator read as one several-file log, in order (the last is diagnose's held-out
// file); each file named tpf_generator_<tag><1-based index>_<pid>.csv.
offline::Log several_file_log(const std::vector<PlanarArmPlant>& plants, const std::string& tag) {
  std::vector<std::filesystem::path> paths;
  for (std::size_t f = 0; f < plants.size(); ++f) {
    paths.push_back(std::filesystem::temp_directory_path() /
                    ("tpf_generator_" + tag + std::to_string(f + 1) + "_" +
                     std::to_string(::getpid()) + ".csv"));
    offline::write_log(paths.back(), generate_planar_log(plants[f]));
  }
  offline::Log log = offline::read_logs(paths);
  for (const auto& p : paths)
    std::filesystem::remove(p);
  return log;
}

// Three files of different motions, each with joint 2's offset given in `offsets`; seeds 31–33,
// the middle file 20 s, the others 60 s.
offline::Log three_file_log(const std::array<double, 3>& offsets) {
  std::vector<PlanarArmPlant> plants(3);
  for (int f = 0; f < 3; ++f) {
    plants[f].seed = 31 + f;
    plants[f].duration_s = f == 1 ? 20.0 : 60.0;
    plants[f].offset = {0.0, offsets[f]};
  }
  return several_file_log(plants, "file");
}

const offline::CandidateTrial* first_trial(const Diagnosis& d, const std::string& key, int joint) {
  for (const offline::CandidateTrial& t : d.trials)
    if (t.key == key && t.joint == joint - 1) return &t;
  return nullptr;
}

TEST(Generator, AnOffsetMissingFromOneFileIsNotClaimed) {
  // 0.4 N·m in files 1 and 3 (a cable on two days), none in file 2: fitted on files 1–2 the
  // offset is confident and helps on the held-out file 3, but file 2 held out in turn gets worse.
  // Not a property of the arm: nothing is claimed, and the findings say why.
  const offline::Log log = three_file_log({0.4, 0.0, 0.4});
  const auto d = offline::diagnose(log, planar_model_x());
  std::printf("  [offset missing from one file] %s\n", describe_claims(d).c_str());
  for (const auto& f : d.findings)
    std::printf("    %s\n", f.c_str());
  EXPECT_TRUE(d.claims.empty()) << describe_claims(d);
  // Nor as a payload against the robot file's inertias: a payload that absorbs the offset
  // (0.058 ± 0.009 kg, −43.9 % on file 3) does not transfer to file 2 either.
  EXPECT_FALSE(d.cad_payload.claimed) << d.cad_payload.mass << " kg";
  std::printf("    CAD payload check: %.3f ± %.3f kg, %.1f %%; %.1f %% on %s held out in turn\n",
              d.cad_payload.mass, d.cad_payload.mass_standard_error,
              100 * d.cad_payload.improvement, 100 * d.cad_payload.transfer_improvement,
              d.cad_payload.transfer_file.c_str());
  const offline::CandidateTrial* offset = first_trial(d, "offset", 2);
  ASSERT_NE(offset, nullptr);
  // It passes every test on the held-out file alone: the transfer is what refuses it.
  EXPECT_GE(offset->improvement, 0.10);
  EXPECT_LT(offset->bic_change, 0.0);
  EXPECT_GE(offset->wald, 3.0);
  EXPECT_LT(offset->transfer_improvement, 0.0);
  EXPECT_NE(offset->transfer_file.find("tpf_generator_file2_"), std::string::npos)
      << offset->transfer_file;
  bool said = false;
  for (const auto& f : d.findings)
    said = said || (f.find("offset") != std::string::npos &&
                    f.find("does not transfer between files") != std::string::npos);
  EXPECT_TRUE(said);
}

TEST(Generator, AnOffsetInEveryFileIsClaimedAcrossFiles) {
  const offline::Log log = three_file_log({0.3, 0.3, 0.3});
  const auto d = offline::diagnose(log, planar_model_x());
  std::printf("  [offset in every file] %s\n", describe_claims(d).c_str());
  EXPECT_NE(outcome(d, "offset", 2), Outcome::Missed) << describe_claims(d);
  expect_only(d, {"offset@2", "asymmetric_friction@2"});
  const offline::CandidateTrial* offset = first_trial(d, "offset", 2);
  ASSERT_NE(offset, nullptr);
  EXPECT_GT(offset->transfer_improvement, 0.10);
}

// Three files, 40 s each: a motion of its own (joint 2 around 0.9 rad), a run (joint 2 around
// 0.1 rad) and the same run again (its noise only differs); file f has a spring of stiffness
// stiffness[f] on joint 2 (neutral 0.3 rad).
std::vector<PlanarArmPlant> repeated_run_plants(const std::array<double, 3>& stiffness) {
  std::vector<PlanarArmPlant> plants(3);
  plants[0].seed = 41;
  plants[0].centre = {0.3, 0.9};
  plants[1].seed = plants[2].seed = 42;
  plants[1].centre = plants[2].centre = {0.3, 0.1};
  plants[2].noise_seed = 99;
  for (int f = 0; f < 3; ++f) {
    plants[f].duration_s = 40.0;
    plants[f].amplitude = {1.2, 1.0};
    plants[f].spring_stiffness = {0.0, stiffness[f]};
    plants[f].spring_neutral = {0.0, 0.3};
  }
  return plants;
}

// The rows of the log's files in `files` (0-based) are diagnose's held-out samples, and only they.
void expect_heldout_files(const offline::Log& log, const Diagnosis& d,
                          const std::set<std::size_t>& files) {
  for (std::size_t f = 0; f < log.file_count(); ++f) {
    const auto [begin, end] = log.file_rows(f);
    for (Eigen::Index k = begin; k < end; ++k)
      if (static_cast<bool>(d.samples.heldout[k]) != (files.count(f) > 0)) {
        ADD_FAILURE() << "row " << k << " of file " << f + 1;
        return;
      }
  }
}

TEST(Generator, AnEffectOfTwoRepeatedRunsIsNotClaimed) {
  // Files 2 and 3 repeat one motion (one seed, other noise) with a spring on joint 2 (a cable
  // on that day); file 1 moves elsewhere without it. Held out one by one, each run would be
  // scored on a fit that saw its own motion; held out together, the spring fitted on the other
  // file does not lower their error, and fitted on them it does not transfer to file 1.
  const offline::Log log = several_file_log(repeated_run_plants({0.0, 1.5, 1.5}), "repeat");
  const auto d = offline::diagnose(log, planar_model_x());
  std::printf("  [spring in two repeated runs only] %s\n", describe_claims(d).c_str());
  for (const auto& f : d.findings)
    std::printf("    %s\n", f.c_str());
  expect_heldout_files(log, d, {1, 2});
  EXPECT_NE(d.heldout_split.find("repeat2_"), std::string::npos) << d.heldout_split;
  EXPECT_NE(d.heldout_split.find("repeats the motion of"), std::string::npos) << d.heldout_split;
  EXPECT_EQ(outcome(d, "spring", 2), Outcome::Missed) << describe_claims(d);
}

TEST(Generator, FilesThatAllRepeatOneMotionAreNotHeldOutByFile) {
  // The run and its repeat alone: no file is independent of the other, so the log is split in
  // interleaved blocks as one file is, and the finding says why.
  std::vector<PlanarArmPlant> plants = repeated_run_plants({0.0, 1.5, 1.5});
  plants.erase(plants.begin());
  const offline::Log log = several_file_log(plants, "alike");
  const auto d = offline::diagnose(log, planar_model_x());
  std::printf("  [one motion twice] %s\n    %s\n", describe_claims(d).c_str(),
              d.heldout_split.c_str());
  EXPECT_EQ(d.samples.heldout_file, 0);
  EXPECT_NE(d.heldout_split.find("Not held out by file"), std::string::npos) << d.heldout_split;
  for (std::size_t f = 0; f < log.file_count(); ++f) {
    const auto [begin, end] = log.file_rows(f);
    const auto held =
        std::count(d.samples.heldout.begin() + begin, d.samples.heldout.begin() + end, char{1});
    EXPECT_GT(held, 0) << "file " << f + 1;
    EXPECT_LT(held, end - begin) << "file " << f + 1;
  }
}

TEST(Generator, ASpringOfEveryFileIsClaimedAndTestedOutsideTheRange) {
  // The same files with the spring in every one: it is the arm's, it transfers between the two
  // motions, and each motion leaves the other's range of q2 (centres 0.9 and 0.1 rad), where the
  // extrapolated k·q must lower the error too.
  const offline::Log log = several_file_log(repeated_run_plants({1.5, 1.5, 1.5}), "spring");
  const auto d = offline::diagnose(log, planar_model_x());
  std::printf("  [spring in every file] %s\n", describe_claims(d).c_str());
  for (const auto& f : d.findings)
    std::printf("    %s\n", f.c_str());
  expect_heldout_files(log, d, {1, 2});
  EXPECT_NE(outcome(d, "spring", 2), Outcome::Missed) << describe_claims(d);
  expect_only(d, {"spring@2", "offset@2"});
  bool tested = false;
  for (const offline::CandidateTrial& t : d.trials)
    if (t.selected && t.key == "spring") {
      tested = true;
      EXPECT_GE(t.outside_improvement, 0.10);
      EXPECT_GT(t.outside_samples, 100);
    }
  EXPECT_TRUE(tested) << describe_claims(d);
  // The declared model diagnose keeps beside its written one (nothing added, as identify fits
  // it) misses the spring: its held-out error on joint 2 is well above the written model's.
  const offline::JointSamples& s = d.samples;
  const Eigen::MatrixXd declared = offline::nominal_residual(d.declared, s);
  double written_sse = 0, declared_sse = 0;
  for (Eigen::Index k = 0; k < s.size(); ++k)
    if (s.valid[k] && s.heldout[k] && std::isfinite(declared(k, 1))) {
      written_sse += d.residual_written(k, 1) * d.residual_written(k, 1);
      declared_sse += declared(k, 1) * declared(k, 1);
    }
  EXPECT_LT(written_sse, 0.8 * declared_sse);
}

// ---- The library's effects, each planted alone on a fresh motion --------------------------------

TEST(Generator, APayloadIsFoundAgainstTheRobotFilesInertias) {
  // 0.5 kg at (0.25, 0, 0.04) m of the forearm (a gripper and part): the identified rigid body
  // absorbs it (it is not a missing effect then: no library claim), the CAD check finds it.
  PlanarArmPlant plant;
  plant.seed = 51;
  plant.payload_mass = 0.5;
  plant.payload_com = {0.25, 0.04};
  const auto d = run(plant, "payload 0.5 kg");
  const offline::CadPayloadCheck& c = d.cad_payload;
  std::printf("    CAD check: %.3f kg at (%.3f, %.3f, %.3f) m, %.1f %% of the held-out SSE\n",
              c.mass, c.centre.x(), c.centre.y(), c.centre.z(), 100 * c.improvement);
  EXPECT_TRUE(d.claims.empty()) << describe_claims(d);
  EXPECT_TRUE(c.claimed);
  EXPECT_NEAR(c.mass, 0.5, 0.05);
  EXPECT_NEAR(c.centre.x(), 0.25, 0.03);
  EXPECT_NEAR(c.centre.z(), 0.04, 0.03);
}

TEST(Generator, FrictionGrowingWithTheJointsOwnLoad) {
  PlanarArmPlant plant;
  plant.seed = 52;
  plant.own_load = {0.05, 0.0};  // joint 1's level grows by 0.05·|G_1| (up to 0.5 N·m)
  const auto d = run(plant, "own-load friction j1");
  EXPECT_NE(outcome(d, "load_friction", 1), Outcome::Missed) << describe_claims(d);
  expect_only(d, {"load_friction@1", "neighbour_load_friction@1"});
  for (const offline::Claim& c : d.claims)
    if (d.groups[c.groups[0]].key == "load_friction") {
      EXPECT_NEAR(c.coefficients[0], 0.05, 0.03);  // α_c
    }
}

TEST(Generator, TemperatureDependentFrictionOfOneJoint) {
  // A cold start under a heavy cycle: joint 2 warms 32 → 46 °C (rise 15 K, 40 s time constant)
  // and its viscous friction falls by 3 %/K (by 42 % over the log). Joint 1 warms too (30 →
  // 41 °C) with a friction that does not depend on it. (At 2 %/K over 9 K the term removes 2.7 %
  // of joint 2's held-out SSE at 1.9 SE: not claimed, docs/identification-tests.md.)
  PlanarArmPlant plant;
  plant.seed = 53;
  plant.log_temperature = true;
  plant.temperature_rise = {12, 15};
  plant.thermal_viscous = {0.0, -0.03};
  const auto d = run(plant, "thermal j2");
  EXPECT_EQ(outcome(d, "thermal", 2), Outcome::Named) << describe_claims(d);
  expect_only(d, {"thermal@2"});
  // β = b_2·(−0.03/K) = −0.006 N·m·s/rad/K: the sign (friction falls as it warms) and size.
  if (!d.claims.empty()) {
    EXPECT_NEAR(d.claims[0].coefficients[0], -0.006, 0.003);
  }
}

TEST(Generator, TemperatureDependentFrictionOfEveryJoint) {
  // Both joints warm by 20 K (40 s time constant), the viscous friction of each falls by 3 %/K:
  // one relative coefficient of every joint. The every-joint form removes only 7.5 % of the
  // weighted held-out SSE of both joints (13 SE): on joint 1 the term is 3.5 % of a residual
  // that its friction memory dominates, so the 10 % rule refuses it there and joint 2's own
  // form (15 %) is what is claimed. Asserted: thermal friction named on joint 2 or on every
  // joint, nothing else claimed.
  PlanarArmPlant plant;
  plant.seed = 54;
  plant.log_temperature = true;
  plant.temperature_rise = {20, 20};
  plant.thermal_viscous = {-0.03, -0.03};
  const auto d = run(plant, "thermal, every joint");
  EXPECT_TRUE(outcome(d, "thermal", 0) == Outcome::Named ||
              outcome(d, "thermal", 2) == Outcome::Named)
      << describe_claims(d);
  expect_only(d, {"thermal"});
}

TEST(Generator, ALoggedTemperatureAloneClaimsNothing) {
  // Both joints warm, friction does not change with it: temperature columns on a clean log.
  PlanarArmPlant plant;
  plant.seed = 55;
  plant.log_temperature = true;
  const auto d = run(plant, "temperature logged, no thermal friction");
  EXPECT_TRUE(d.claims.empty()) << describe_claims(d);
}

TEST(Generator, MotionCouplingBetweenTheJoints) {
  // Joint 1 gets 0.15 N·m·s/rad × q̇_2: the drag of joint 2's belt drive, which runs through
  // joint 1's axis from a motor at the base.
  PlanarArmPlant plant;
  plant.seed = 56;
  plant.coupling_velocity(0, 1) = 0.15;
  const auto d = run(plant, "coupling j1 <- dq2");
  EXPECT_EQ(outcome(d, "coupling", 1), Outcome::Named) << describe_claims(d);
  expect_only(d, {"coupling@1"});
  if (!d.claims.empty()) {
    EXPECT_NEAR(d.claims[0].coefficients[0], 0.15, 0.05);  // C_v,12
    EXPECT_NEAR(d.claims[0].coefficients[1], 0.0, 0.05);   // C_a,12: none planted
  }
  expect_written_model_runs(d);
}

TEST(Generator, MotorSideRipple) {
  // 0.08 N·m at 2 periods per motor revolution on joint 2 (gear ratio 100 of the robot file):
  // 200 periods per output revolution, far above the output-ripple search (≤ 64).
  PlanarArmPlant plant;
  plant.seed = 57;
  plant.motor_ripple_amplitude = {0.0, 0.08};
  const auto d = run(plant, "motor ripple j2");
  EXPECT_EQ(outcome(d, "ripple_motor", 2), Outcome::Named) << describe_claims(d);
  expect_only(d, {"ripple_motor@2"});
  if (!d.claims.empty()) {  // a·sin(n r q + 0.7) = a cos 0.7·sin + a sin 0.7·cos
    EXPECT_NEAR(d.claims[0].coefficients[0], 0.08 * std::cos(0.7), 0.01);
    EXPECT_NEAR(d.claims[0].coefficients[1], 0.08 * std::sin(0.7), 0.01);
  }
  const double f = written_ripple_cycles(d, 2, true);  // fitted as a real number
  std::printf("    written: %.4f periods/motor rev (planted 2)\n", f);
  EXPECT_LT(std::abs(f - 2.0) / 2.0, 0.03) << f;
  expect_written_model_runs(d);
}

TEST(Generator, DirectionAsymmetricViscousFriction) {
  // Joint 2: b = 0.30 forward, 0.10 backward (a seal that drags one way).
  PlanarArmPlant plant;
  plant.seed = 58;
  plant.viscous = {0.30, 0.20};
  plant.viscous_asymmetry = {0.0, 0.10};
  const auto d = run(plant, "asymmetric viscous j2");
  EXPECT_NE(outcome(d, "asymmetric_friction", 2), Outcome::Missed) << describe_claims(d);
  expect_only(d, {"asymmetric_friction@2", "offset@2"});
  // Ambiguous with the offset by construction: the family's Coulomb column |sgn q̇| is the
  // offset's column on moving samples (their smallest principal angle is nearly zero), although
  // the viscous part |q̇| is what this log holds; its coefficient is the planted a_v.
  for (const offline::Claim& c : d.claims)
    if (d.groups[c.groups[0]].key == "asymmetric_friction") {
      EXPECT_NEAR(c.coefficients[1], 0.10, 0.03);
    }
  // Judged beside the selected friction term, no payload (0.016 kg at (−0.32, 0, −0.34) m,
  // −20.4 %, when it was judged alone).
  expect_no_unplanted_payload(d, {"asymmetric_friction@2", "offset@2"});
}

// Acceleration coupling: with an identified rigid body (base parameters and armatures), [0; q̈_1]
// on joint 2 is [q̈_2; q̈_1] (in the rigid body's span) minus [q̈_2; 0], the same column as −C·q̈_2
// on joint 1. The planted joint is named, or the claim is ambiguous and lists it; never a
// confident name of joint 1 alone.
void expect_acceleration_coupling_of_joint_2(const Diagnosis& d,
                                             const std::set<std::string>& planted) {
  EXPECT_NE(outcome(d, "coupling", 2), Outcome::Missed) << describe_claims(d);
  expect_only(d, planted);
  for (const offline::Claim& c : d.claims)
    for (std::size_t i = 0; i < c.groups.size(); ++i)
      std::printf("    %s: %.1f %% of the held-out SSE of %s\n",
                  d.groups[c.groups[i]].title.c_str(), 100 * c.improvements[i],
                  c.scored_joints.empty() ? "its joint" : "joints 1 and 2");
}

TEST(Generator, AccelerationCouplingAloneIsNotNamedOnTheOtherJoint) {
  // τ_2 += 0.1·q̈_1: a base-mounted elbow motor whose rotor turns with the forearm's absolute
  // angle.
  PlanarArmPlant plant;
  plant.seed = 56;
  plant.coupling_acceleration(1, 0) = 0.1;
  const auto d = run(plant, "coupling j2 <- ddq1");
  expect_acceleration_coupling_of_joint_2(d, {"coupling@2"});
}

TEST(Generator, AccelerationCouplingBesideVelocityCouplingIsNotNamedOnTheOtherJoint) {
  // The same, with joint 1's belt drag 0.15·q̇_2 of MotionCouplingBetweenTheJoints: coupling of
  // joint 1 is planted too, but joint 2's must not be absorbed into it unseen.
  PlanarArmPlant plant;
  plant.seed = 56;
  plant.coupling_velocity(0, 1) = 0.15;
  plant.coupling_acceleration(1, 0) = 0.1;
  const auto d = run(plant, "coupling j1 <- dq2, j2 <- ddq1");
  expect_acceleration_coupling_of_joint_2(d, {"coupling@1", "coupling@2"});
}

}  // namespace
}  // namespace tpf::test
