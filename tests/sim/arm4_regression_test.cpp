// The 4-DoF arm's twin does not move: short runs of the four shipped arm4 scenarios give the
// numbers the twin gave before it became generic over the joint count (values pinned from that
// code, commit 357ed50). Sums over whole columns catch a change anywhere in the run; the last
// row catches drift. Quantised columns (q, i, p) are compared to a few ulps of their sum, the
// ground truth to 1e-9 relative.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "offline/sim/scenario.hpp"
#include "offline/sim/simulate.hpp"

namespace {

using namespace tpf::offline;

struct Pinned {
  const char* scenario;
  std::uint64_t seed;
  double duration_s;
  long rows;
  double sum_q, sum_i, sum_p, sum_tau_ext, sum_fric;
  double last_q1, last_q4, last_i2, last_i3;
};

double column_sum(const Log& log, const char* prefix, int count) {
  double s = 0.0;
  for (int j = 1; j <= count; ++j)
    s += log.col(indexed_name(prefix, j)).sum();
  return s;
}

void expect_close(double actual, double expected, double relative, const std::string& what) {
  EXPECT_NEAR(actual, expected, relative * std::max(1.0, std::abs(expected))) << what;
}

// Pinned on the twin as of 357ed50 (4 joints hard-wired), Release build.
const Pinned kPinned[] = {
    {"excitation.json", 21, 2.5, 997, 21.54832260650694, -1371832, 1601.1870000000008, 0,
     278740.08312744164, 0.003592730723956745, -0.1478339842667846, -1169, -371},
    {"excitation-undeclared.json", 22, 2.5, 998, -107.30343758468874, -2182547, 2062.8090000000007,
     0, 194576.54449787689, 0.001527223513319592, -0.28657347769400621, -2144, -707},
    {"static-contacts.json", 23, 4, 1600, -160.01226485360303, -2406913, 12935.191500000004,
     -759.45781584342137, 3225.7794686000216, -0.0, 0, -743, -535},
    {"teaching.json", 24, 4, 1598, -389.39430771637944, -2274146, 12719.9625, -1530.0394225528898,
     -442291.02429834614, -6.2591127595065242e-06, -0.0, -540, -375},
};

TEST(Arm4Regression, ShortRunsGiveThePinnedNumbers) {
  for (const Pinned& p : kPinned) {
    const Scenario s = load_scenario(std::string(TPF_TEST_DATA_DIR "/scenarios/") + p.scenario);
    const Log log = simulate_to_log(s, p.seed, p.duration_s);
    const Eigen::Index last = log.rows() - 1;
    const double sum_q = column_sum(log, "q", 4), sum_i = column_sum(log, "i", 4);
    const double sum_p = column_sum(log, "p", 11), sum_tau = column_sum(log, "gt_tau_ext", 4);
    const double sum_fric = column_sum(log, "gt_fric", 4);
    const std::string at = std::string(" in ") + p.scenario;
    EXPECT_EQ(log.rows(), p.rows) << at;
    expect_close(sum_q, p.sum_q, 1e-12, "sum q" + at);
    expect_close(sum_i, p.sum_i, 1e-12, "sum i" + at);
    expect_close(sum_p, p.sum_p, 1e-12, "sum p" + at);
    expect_close(sum_tau, p.sum_tau_ext, 1e-9, "sum gt_tau_ext" + at);
    expect_close(sum_fric, p.sum_fric, 1e-9, "sum gt_fric" + at);
    expect_close(log.col("q1")(last), p.last_q1, 1e-12, "last q1" + at);
    expect_close(log.col("q4")(last), p.last_q4, 1e-12, "last q4" + at);
    expect_close(log.col("i2")(last), p.last_i2, 1e-12, "last i2" + at);
    expect_close(log.col("i3")(last), p.last_i3, 1e-12, "last i3" + at);
  }
}

}  // namespace
