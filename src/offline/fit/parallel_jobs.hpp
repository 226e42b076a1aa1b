// Independent jobs of unequal cost (a Ceres fit per joint, a residual analysis per joint) on two
// threads, each taking the next job when it is free: the wall time of the slowest half of a fixed
// split (parallel_halves) is the slowest job's instead.
#pragma once

#include <atomic>
#include <exception>
#include <thread>
#include <vector>

namespace tpf::offline {

/// Runs job(i) for every i in [0, count) on the calling thread and one helper, in whatever order
/// they come free. Each job must only write to its own outputs (slot i): the result is then that
/// of a serial pass, whatever the scheduling. After all jobs have run, the exception of the
/// lowest-numbered job that threw is rethrown (the one a serial pass would have met first).
template <typename Job>
void parallel_jobs(int count, Job&& job) {
  if (count <= 0) return;
  std::vector<std::exception_ptr> errors(static_cast<std::size_t>(count));
  std::atomic<int> next{0};
  const auto take_jobs = [&] {
    for (int i = next.fetch_add(1); i < count; i = next.fetch_add(1)) {
      try {
        job(i);
      } catch (...) {
        errors[static_cast<std::size_t>(i)] = std::current_exception();
      }
    }
  };
  if (count > 1) {
    std::thread helper(take_jobs);
    take_jobs();
    helper.join();
  } else {
    take_jobs();
  }
  for (const std::exception_ptr& error : errors)
    if (error) std::rethrow_exception(error);
}

}  // namespace tpf::offline
