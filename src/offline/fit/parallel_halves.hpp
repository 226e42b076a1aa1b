// The one parallel pattern of the offline passes over a log: two halves of the samples on two
// threads (the machine budget of identification is 2 cores), results merged by the caller.
#pragma once

#include <Eigen/Core>
#include <exception>
#include <thread>

namespace tpf::offline {

/// Runs work(n/2, n) on a helper thread and work(0, n/2) on the calling thread, then joins.
/// `work(begin, end)` must only write to its own rows (or to per-half outputs): the result is
/// then identical to a serial pass, whatever the scheduling. An exception of either half is
/// rethrown after both have finished (the first half's when both throw, as a serial pass would).
template <typename Work>
void parallel_halves(Eigen::Index n, Work&& work) {
  const Eigen::Index middle = n / 2;
  std::exception_ptr helper_error;
  std::thread helper([&] {
    try {
      work(middle, n);
    } catch (...) {
      helper_error = std::current_exception();
    }
  });
  try {
    work(Eigen::Index{0}, middle);
  } catch (...) {
    helper.join();
    throw;
  }
  helper.join();
  if (helper_error) std::rethrow_exception(helper_error);
}

}  // namespace tpf::offline
