#include "offline/fit/parallel_jobs.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace tpf::offline {
namespace {

/// A job of uneven cost whose result depends only on its number.
double uneven_job(int i) {
  double x = i;
  for (int k = 0; k < 1000 * (i % 5 + 1); ++k)
    x = std::sin(x) + 0.5 * i;
  return x;
}

TEST(ParallelJobs, EveryJobOnceSameResultAsSerial) {
  constexpr int kJobs = 37;
  std::vector<double> serial(kJobs), parallel(kJobs);
  for (int i = 0; i < kJobs; ++i)
    serial[i] = uneven_job(i);
  std::vector<std::atomic<int>> runs(kJobs);
  parallel_jobs(kJobs, [&](int i) {
    ++runs[static_cast<std::size_t>(i)];
    parallel[static_cast<std::size_t>(i)] = uneven_job(i);
  });
  for (int i = 0; i < kJobs; ++i) {
    EXPECT_EQ(runs[static_cast<std::size_t>(i)].load(), 1) << i;
    EXPECT_EQ(parallel[static_cast<std::size_t>(i)], serial[static_cast<std::size_t>(i)]) << i;
  }
}

TEST(ParallelJobs, NoJobAndOneJob) {
  int calls = 0;
  parallel_jobs(0, [&](int) { ++calls; });
  EXPECT_EQ(calls, 0);
  parallel_jobs(1, [&](int i) { calls += 1 + i; });
  EXPECT_EQ(calls, 1);
}

TEST(ParallelJobs, RethrowsTheLowestNumberedJobsErrorAfterAllHaveRun) {
  std::atomic<int> finished{0};
  try {
    parallel_jobs(8, [&](int i) {
      ++finished;
      if (i == 6 || i == 3) throw std::runtime_error("job " + std::to_string(i));
    });
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "job 3");  // the one a serial pass meets first
  }
  EXPECT_EQ(finished.load(), 8);
}

}  // namespace
}  // namespace tpf::offline
