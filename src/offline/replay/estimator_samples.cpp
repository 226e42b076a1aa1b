#include "offline/replay/estimator_samples.hpp"

#include <array>

#include "tpf/common/error.hpp"
#include "tpf/common/joint_counts.hpp"
#include "tpf/model/effort_unit.hpp"

namespace tpf::offline {

template <int N>
std::vector<ReplaySample<N>> estimator_samples(const Log& log, const Model<double, N>& model,
                                               int P) {
  if (log.joint_count() != N) {
    throw Error::at(log.source, 0, "columns",
                    "the log has " + std::to_string(log.joint_count()) + " joints, expected " +
                        std::to_string(N));
  }
  const int pads = log.pad_count();
  if (pads != 0 && P != 0 && pads != P) {
    throw Error::at(log.source, 0, "columns",
                    "the log has " + std::to_string(pads) + " pad columns, the pad layout has " +
                        std::to_string(P));
  }
  const std::string effort = log.effort_prefix();
  const bool current = effort_unit_of_column(effort) == EffortUnit::Milliampere;
  const int t = log.column("t");
  std::array<int, N> q{}, dq{}, e{};
  for (int j = 0; j < N; ++j) {
    q[j] = log.column(indexed_name("q", j + 1));
    dq[j] = log.column(indexed_name("dq", j + 1));
    e[j] = log.column(indexed_name(effort, j + 1));
  }
  std::vector<int> p(static_cast<std::size_t>(P));
  for (int k = 0; k < P; ++k)
    p[static_cast<std::size_t>(k)] = pads ? log.column(indexed_name("p", k + 1)) : -1;

  std::vector<ReplaySample<N>> samples(static_cast<std::size_t>(log.rows()));
  for (Eigen::Index r = 0; r < log.rows(); ++r) {
    auto& s = samples[static_cast<std::size_t>(r)];
    s.t = log.values(r, t);
    for (int j = 0; j < N; ++j) {
      s.q[j] = log.values(r, q[j]);
      s.dq[j] = log.values(r, dq[j]);
      s.effort[j] = log.values(r, e[j]);
    }
    if (current) s.effort = torque_from_current(model, s.effort);
    s.pressure.resize(P);
    for (int k = 0; k < P; ++k) {
      const int c = p[static_cast<std::size_t>(k)];
      s.pressure[k] = c >= 0 ? log.values(r, c) : 0.0;
    }
  }
  return samples;
}

#define TPF_INSTANTIATE_ESTIMATOR_SAMPLES(N)                                                      \
  template std::vector<ReplaySample<N>> estimator_samples<N>(const Log&, const Model<double, N>&, \
                                                             int);
TPF_FOR_EACH_JOINT_COUNT(TPF_INSTANTIATE_ESTIMATOR_SAMPLES)
#undef TPF_INSTANTIATE_ESTIMATOR_SAMPLES

}  // namespace tpf::offline
