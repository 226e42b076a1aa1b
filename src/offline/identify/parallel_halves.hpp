// The one parallel pattern of the offline passes over a log: two halves of the samples on two
// threads (the machine budget of identification is 2 cores), results merged by the caller.
#pragma once

#include <Eigen/Core>
#include <thread>

namespace tpf::offline {

/// Runs work(n/2, n) on a helper thread and work(0, n/2) on the calling thread, then joins.
/// `work(begin, end)` must only write to its own rows (or to per-half outputs): the result is
/// then identical to a serial pass, whatever the scheduling.
template <typename Work>
void parallel_halves(Eigen::Index n, Work&& work) {
  const Eigen::Index middle = n / 2;
  std::thread helper([&] { work(middle, n); });
  work(Eigen::Index{0}, middle);
  helper.join();
}

}  // namespace tpf::offline
