#include "offline/replay/estimator_samples.hpp"

#include "tpf/common/error.hpp"
#include "tpf/model/effort_unit.hpp"

namespace tpf::offline {

std::vector<ReplaySample> estimator_samples(const Log& log,
                                            const Model<double, Eigen::Dynamic>& model, int P) {
  const int n = model.joint_count();
  if (log.joint_count() != n) {
    throw Error::at(log.source, 0, "columns",
                    "the log has " + std::to_string(log.joint_count()) + " joints, expected " +
                        std::to_string(n));
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
  std::vector<int> q(static_cast<std::size_t>(n)), dq(q), e(q);
  for (int j = 0; j < n; ++j) {
    const auto uj = static_cast<std::size_t>(j);
    q[uj] = log.column(indexed_name("q", j + 1));
    dq[uj] = log.column(indexed_name("dq", j + 1));
    e[uj] = log.column(indexed_name(effort, j + 1));
  }
  std::vector<int> p(static_cast<std::size_t>(P));
  for (int k = 0; k < P; ++k)
    p[static_cast<std::size_t>(k)] = pads ? log.column(indexed_name("p", k + 1)) : -1;

  std::vector<ReplaySample> samples(static_cast<std::size_t>(log.rows()));
  for (Eigen::Index r = 0; r < log.rows(); ++r) {
    auto& s = samples[static_cast<std::size_t>(r)];
    s.resize(n, P);
    s.t = log.values(r, t);
    for (int j = 0; j < n; ++j) {
      const auto uj = static_cast<std::size_t>(j);
      s.q[j] = log.values(r, q[uj]);
      s.dq[j] = log.values(r, dq[uj]);
      s.effort[j] = log.values(r, e[uj]);
    }
    if (current) s.effort = torque_from_current(model, s.effort);
    for (int k = 0; k < P; ++k) {
      const int c = p[static_cast<std::size_t>(k)];
      s.pressure[k] = c >= 0 ? log.values(r, c) : 0.0;
    }
  }
  return samples;
}

}  // namespace tpf::offline
