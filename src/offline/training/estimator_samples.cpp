#include "offline/training/estimator_samples.hpp"

#include <array>

#include "tpf/common/error.hpp"

namespace tpf::offline {

template <int N, int P>
std::vector<EstimatorSample<double, N, P>> estimator_samples(const Log& log) {
  if (log.joint_count() != N) {
    throw Error::at(log.source, 0, "columns",
                    "the log has " + std::to_string(log.joint_count()) + " joints, expected " +
                        std::to_string(N));
  }
  const int pads = log.pad_count();
  if (pads != 0 && pads != P) {
    throw Error::at(log.source, 0, "columns",
                    "the log has " + std::to_string(pads) + " pad columns, the pad layout has " +
                        std::to_string(P));
  }
  const std::string effort = log.effort_prefix();
  const int t = log.column("t");
  std::array<int, N> q{}, dq{}, e{};
  for (int j = 0; j < N; ++j) {
    q[j] = log.column(indexed_name("q", j + 1));
    dq[j] = log.column(indexed_name("dq", j + 1));
    e[j] = log.column(indexed_name(effort, j + 1));
  }
  std::array<int, P> p{};
  for (int k = 0; k < P; ++k)
    p[k] = pads ? log.column(indexed_name("p", k + 1)) : -1;

  std::vector<EstimatorSample<double, N, P>> samples(static_cast<std::size_t>(log.rows()));
  for (Eigen::Index r = 0; r < log.rows(); ++r) {
    auto& s = samples[static_cast<std::size_t>(r)];
    s.t = log.values(r, t);
    for (int j = 0; j < N; ++j) {
      s.q[j] = log.values(r, q[j]);
      s.dq[j] = log.values(r, dq[j]);
      s.effort[j] = log.values(r, e[j]);
    }
    for (int k = 0; k < P; ++k)
      s.pressure[k] = p[k] >= 0 ? log.values(r, p[k]) : 0.0;
  }
  return samples;
}

template std::vector<EstimatorSample<double, 4, 11>> estimator_samples<4, 11>(const Log&);

}  // namespace tpf::offline
