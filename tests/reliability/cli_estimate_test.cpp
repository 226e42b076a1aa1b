// The built `tpf estimate` on twin logs: the est_* columns it writes against the ground truth and
// against the same estimator run through the library, its contact episodes against the twin's
// contacts, no episode on a contact-free log, and bad input refused with no output left behind.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "offline/log/read_log.hpp"
#include "offline/replay/estimator_samples.hpp"
#include "offline/replay/replay_estimator.hpp"
#include "tpf/estimation/estimator_parameter_file.hpp"
#include "tpf/estimation/estimator_status.hpp"
#include "tpf/estimation/load_estimator.hpp"
#include "tpf/estimation/nominal_model.hpp"
#include "tpf/friction/friction_file.hpp"
#include "tpf/model/load_robot.hpp"

namespace tpf::test {
namespace {

const std::string kEstimateFiles = " --params " + kShippedData + "/arm4.params.json --estimator " +
                                   kShippedData + "/arm4.estimator.json --weights " + kShippedData +
                                   "/weights/arm4.tcn.json";

/// A twin log of `scenario` (data/scenarios/<scenario>.json), simulated into `box` as `out`.
void simulate(const CliSandbox& box, const std::string& scenario, int seed, double seconds,
              const std::string& out) {
  const CliResult r =
      box.tpf("simulate --scenario " + kShippedData + "/scenarios/" + scenario + ".json --seed " +
              std::to_string(seed) + " --duration " + std::to_string(seconds) + " --out " + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
}

struct Interval {
  double start, end;
};

/// The runs of rows where `flag` is nonzero: [t of the first, t of the first row after).
std::vector<Interval> runs_of(const Eigen::VectorXd& t, const Eigen::VectorXd& flag) {
  std::vector<Interval> runs;
  bool in = false;
  for (Eigen::Index r = 0; r < t.size(); ++r) {
    if (!std::isfinite(flag[r])) continue;
    if (flag[r] != 0.0 && !in) runs.push_back({t[r], t[t.size() - 1]});
    if (flag[r] == 0.0 && in) runs.back().end = t[r];
    in = flag[r] != 0.0;
  }
  return runs;
}

/// Bitwise equality of doubles (NaN equals NaN of the same bits).
bool same_bits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

TEST(CliEstimate, StaticContactsMatchTheGroundTruthAndTheLibraryBitForBit) {
  CliSandbox box("estimate_contacts");
  simulate(box, "static-contacts", 4, 40.0, "contacts.csv");
  const CliResult r = box.tpf("estimate --log contacts.csv" + kEstimateFiles +
                              " --out contacts.est.csv --json contacts.json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("(SIMULATED)"), std::string::npos) << r.out;
  ASSERT_TRUE(std::filesystem::exists(box / "contacts.est.html"));
  EXPECT_NE(CliSandbox::slurp(box / "contacts.est.html").find("<svg"), std::string::npos);
  const offline::Log est = offline::read_log(box / "contacts.est.csv");
  const offline::Log input = offline::read_log(box / "contacts.csv");
  ASSERT_EQ(est.rows(), input.rows());
  const Eigen::VectorXd t = est.col("t");

  // τ̂_ext against gt_tau_ext: the fusion's accuracy on the twin's pushes (docs/evaluation.md:
  // |F| RMSE ≈ 4 N), here ≤ 40 % of the true torque's RMS and correlated with it by ≥ 0.9 on
  // every pushed joint (joint 4 is never pushed: its estimate stays below 0.05 N·m RMS).
  for (int j = 1; j <= 4; ++j) {
    const Eigen::VectorXd e = est.col(offline::indexed_name("est_tau_ext", j));
    const Eigen::VectorXd g = est.col(offline::indexed_name("gt_tau_ext", j));
    const Eigen::Array<bool, Eigen::Dynamic, 1> ok = e.array().isFinite();
    ASSERT_GT(ok.count(), est.rows() * 99 / 100);
    const Eigen::VectorXd ef = ok.select(e, 0.0), gf = ok.select(g, 0.0);
    const double n = static_cast<double>(ok.count());
    const double rmse = std::sqrt((ef - gf).squaredNorm() / n);
    const double rms = std::sqrt(gf.squaredNorm() / n);
    if (rms < 1e-9) {
      EXPECT_LT(rmse, 0.05) << "joint " << j;
      continue;
    }
    const Eigen::ArrayXd ec = ef.array() - ef.sum() / n, gc = gf.array() - gf.sum() / n;
    const double correlation = (ec * gc).sum() / std::sqrt(ec.square().sum() * gc.square().sum());
    EXPECT_LT(rmse, 0.4 * rms) << "joint " << j;
    EXPECT_GT(correlation, 0.9) << "joint " << j;
  }

  // Episodes against the twin's contacts: each push found once, its start within 0.1 s (the
  // pad's latency is ≈ 40 ms) and its end within 0.1 s; the estimator's other episodes are the
  // torque-only alarm's short ones as the arm starts off to its next pose (< 0.25 s each).
  const auto json = nlohmann::json::parse(CliSandbox::slurp(box / "contacts.json"));
  const std::vector<Interval> truth = runs_of(t, est.col("gt_contact"));
  ASSERT_GE(truth.size(), 6u);
  int matched = 0, short_extra = 0;
  for (const auto& e : json["episodes"]) {
    const double start = e["start_s"], end = e["end_s"];
    bool found = false;
    for (const Interval& g : truth)
      found = found || (std::abs(start - g.start) < 0.1 && std::abs(end - g.end) < 0.1);
    matched += found;
    short_extra += !found && end - start < 0.25;
    EXPECT_TRUE(found || end - start < 0.25) << "episode " << start << " … " << end;
    EXPECT_EQ(e["peak_abs_tau_ext_nm"].size(), 4u);
  }
  EXPECT_EQ(matched, static_cast<int>(truth.size()));
  EXPECT_LE(short_extra, 2);
  EXPECT_NE(r.out.find(std::to_string(json["episodes"].size()) + " contact episodes"),
            std::string::npos)
      << r.out;

  // The same estimator through the library: the core loader, make_replay_estimator, one update
  // per row; every est_* value read back is the output's, bit for bit.
  EstimatorFiles files{kShippedData + "/arm4.params.json", kShippedData + "/arm4.robot.json",
                       kShippedData + "/arm4.pads.json", kShippedData + "/arm4.estimator.json",
                       kShippedData + "/weights/arm4.tcn.json"};
  const offline::ReplaySetup setup = load_estimator_setup(files);
  auto estimator = offline::make_replay_estimator(setup);
  const auto samples = offline::estimator_samples(input, setup.nominal.model, 11);
  const double nan = std::nan("");
  long mismatches = 0, gated = 0;
  for (std::size_t k = 0; k < samples.size(); ++k) {
    const auto& out = estimator->update(samples[k]);
    const auto row = static_cast<Eigen::Index>(k);
    const bool present = (out.status & (kStatusNonFiniteInput | kStatusStaleTime)) == 0;
    std::vector<std::pair<std::string, double>> expected;
    for (int j = 0; j < 4; ++j)
      expected.emplace_back(offline::indexed_name("est_tau_ext", j + 1),
                            present ? out.external.torque[j] : nan);
    expected.emplace_back("est_contact", present ? double(out.contact) : nan);
    expected.emplace_back("est_pad", present ? double(out.wrench.pad + 1) : nan);
    const char* axes[] = {"est_fx", "est_fy", "est_fz"};
    for (int a = 0; a < 3; ++a)
      expected.emplace_back(axes[a], !present              ? nan
                                     : out.wrench.pad >= 0 ? out.wrench.force_world[a]
                                                           : 0.0);
    expected.emplace_back("est_status", double(out.status));
    for (const auto& [name, value] : expected)
      mismatches += !same_bits(est.col(name)[row], value);
    gated += (out.status & kStatusCompensatorGated) != 0;
  }
  EXPECT_EQ(mismatches, 0);
  EXPECT_EQ(gated, 0);  // the shipped networks pass the held-out gate on every joint
}

TEST(CliEstimate, AContactFreeLogHasNoEpisode) {
  CliSandbox box("estimate_contact_free");
  simulate(box, "excitation", 7, 30.0, "free.csv.gz");
  const CliResult r = box.tpf("estimate --log free.csv.gz" + kEstimateFiles +
                              " --out free.est.csv.gz --json f.json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("0 contact episodes"), std::string::npos) << r.out;
  EXPECT_TRUE(std::filesystem::exists(box / "free.est.html"));
  const auto json = nlohmann::json::parse(CliSandbox::slurp(box / "f.json"));
  EXPECT_EQ(json["episodes"].size(), 0u);
  EXPECT_EQ(json["contact_cycles"], 0);
  const offline::Log est = offline::read_log(box / "free.est.csv.gz");
  EXPECT_EQ(est.col("est_contact").maxCoeff(), 0.0);
  EXPECT_EQ(est.col("est_pad").maxCoeff(), 0.0);
  // Replayed again over its own output: the est_* columns are replaced, not doubled.
  const CliResult again =
      box.tpf("estimate --log free.est.csv.gz" + kEstimateFiles + " --out again.csv");
  ASSERT_EQ(again.exit_code, 0) << again.err;
  const offline::Log twice = offline::read_log(box / "again.csv");
  EXPECT_EQ(twice.columns, est.columns);
  EXPECT_TRUE(twice.values.cwiseEqual(est.values).count() +
                  (twice.values.array().isNaN() && est.values.array().isNaN()).count() ==
              est.values.size());
}

TEST(CliEstimate, AMeasuredContactFreeLogHasNoEpisode) {
  // The Kinova Gen3 logs (MEASURED, MIT, data/real/kinova-gen3): a model identified on the three
  // fitting files, the estimator calibrated on one of them, replayed over a held-out file.
  CliSandbox box("estimate_measured");
  const std::string gen3 = kShippedData + "/real/kinova-gen3/";
  const std::string logs = gen3 + "logs/";
  const std::string robot = " --robot " + gen3 + "gen3.robot.json";
  const CliResult identify = box.tpf(
      "identify --quiet --log " + logs + "RunTrajectory1.csv.gz " + logs + "Trajectory1.csv.gz " +
      logs + "RecordTrajectory_quadratic.csv.gz" + robot + " --out gen3.params.json");
  ASSERT_EQ(identify.exit_code, 0) << identify.err;
  const std::string model = " --params gen3.params.json" + robot;
  const CliResult calibrate =
      box.tpf("calibrate --log " + logs + "RunTrajectory1.csv.gz" + model + " --out gen3.e.json");
  ASSERT_EQ(calibrate.exit_code, 0) << calibrate.err;
  const CliResult r = box.tpf("estimate --log " + logs + "opti_traj_testing1.csv.gz" + model +
                              " --estimator gen3.e.json --out measured.est.csv");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("(MEASURED), 4741 rows"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("0 contact episodes"), std::string::npos) << r.out;
  const offline::Log est = offline::read_log(box / "measured.est.csv");
  EXPECT_EQ(est.col("est_contact").maxCoeff(), 0.0);
  EXPECT_TRUE(est.col("est_tau_ext7").allFinite());
  const std::string page = CliSandbox::slurp(box / "measured.est.html");
  EXPECT_NE(page.find("MEASURED"), std::string::npos);
  EXPECT_NE(page.find("MIT"), std::string::npos);  // the licence, from the log's metadata
}

TEST(CliEstimate, BadInputIsRefusedNamingTheFileAndLeavesNoOutput) {
  CliSandbox box("estimate_bad_input");
  simulate(box, "excitation", 3, 2.0, "arm4.csv");
  save_estimator_parameters(
      box / "arm9.estimator.json",
      [] {
        EstimatorParameters<double, Eigen::Dynamic> p;
        p.resize(9);
        return p;
      }(),
      "default parameters of a 9-joint arm");
  const std::string arm9 = kShippedData + "/../tests/sim/arm9/";
  const std::string arm9_robot = arm9 + "arm9.robot.json";
  save_nominal_model(box / "arm9.params.json",
                     nominal_from_model(load_robot<double, Eigen::Dynamic>(arm9_robot),
                                        load_stribeck_parameters(arm9 + "arm9.friction.json", 9)),
                     "true model of tests/sim/arm9");
  const std::vector<std::string> before = box.files();
  struct Case {
    std::string args, message;
  };
  const std::vector<Case> cases{
      {"--estimator " + kShippedData + "/arm4.estimator.json", "--params is required"},
      {"--params missing.params.json --estimator " + kShippedData + "/arm4.estimator.json",
       "missing.params.json"},
      {"--params " + kShippedData + "/arm4.params.json --estimator arm9.estimator.json",
       "arm9.estimator.json: joints"},
      {"--params " + kShippedData + "/arm4.params.json --estimator " + kShippedData +
           "/arm4.estimator.json --robot " + arm9_robot,
       "arm4.params.json"},
      {"--params arm9.params.json --estimator arm9.estimator.json --robot " + arm9_robot,
       "arm4.csv: the log has 4 joints"},
  };
  for (const Case& c : cases) {
    const CliResult r = box.tpf("estimate --log arm4.csv " + c.args + " --out out.csv");
    EXPECT_NE(r.exit_code, 0) << c.args;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << c.args << "\n" << r.err;
    EXPECT_EQ(box.files(), before) << c.args;  // no output, no temporary
  }
}

}  // namespace
}  // namespace tpf::test
