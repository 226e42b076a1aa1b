#include "offline/samples/repeated_motion.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "offline/samples/joint_samples.hpp"

namespace tpf::offline {

std::vector<RepeatedMotion> repeated_motions(const Log& log, const JointSamples& s,
                                             double tolerance) {
  std::vector<RepeatedMotion> out;
  for (std::size_t a = 0; a < log.file_count(); ++a)
    for (std::size_t b = a + 1; b < log.file_count(); ++b) {
      const Eigen::Index a0 = log.file_rows(a).first, b0 = log.file_rows(b).first;
      const Eigen::Index n = std::min(log.file_rows(a).second - a0, log.file_rows(b).second - b0);
      RepeatedMotion r{a, b, 0, 0.0, 0.0, std::vector<double>(s.joints(), 0.0)};
      std::vector<double> dq2(s.joints(), 0.0);
      for (Eigen::Index k = 0; k < n; ++k) {
        if (!s.valid[a0 + k] || !s.valid[b0 + k]) continue;
        ++r.common_samples;
        for (int j = 0; j < s.joints(); ++j) {
          const double d = s.q(a0 + k, j) - s.q(b0 + k, j);
          const double e = s.effort(a0 + k, j) - s.effort(b0 + k, j);
          dq2[j] += d * d;
          r.torque_rms_difference[j] += e * e;
          r.max_position_difference = std::max(r.max_position_difference, std::abs(d));
        }
      }
      if (r.common_samples == 0) continue;
      const double count = static_cast<double>(r.common_samples);
      for (int j = 0; j < s.joints(); ++j) {
        r.rms_position_difference = std::max(r.rms_position_difference, std::sqrt(dq2[j] / count));
        r.torque_rms_difference[j] = std::sqrt(r.torque_rms_difference[j] / count);
      }
      if (r.rms_position_difference < tolerance) out.push_back(r);
    }
  return out;
}

std::vector<std::vector<std::size_t>> repeated_motion_groups(
    std::size_t files, const std::vector<RepeatedMotion>& repeats) {
  std::vector<std::size_t> root(files);
  for (std::size_t f = 0; f < files; ++f)
    root[f] = f;
  const auto find = [&](std::size_t f) {
    while (root[f] != f)
      f = root[f] = root[root[f]];
    return f;
  };
  for (const RepeatedMotion& r : repeats) {
    const std::size_t a = find(r.first), b = find(r.second);
    root[std::max(a, b)] = std::min(a, b);
  }
  std::vector<std::vector<std::size_t>> groups;
  std::vector<int> index(files, -1);
  for (std::size_t f = 0; f < files; ++f) {
    const std::size_t r = find(f);
    if (index[r] < 0) {
      index[r] = static_cast<int>(groups.size());
      groups.emplace_back();
    }
    groups[static_cast<std::size_t>(index[r])].push_back(f);
  }
  return groups;
}

std::vector<std::pair<double, double>> position_range(const JointSamples& s,
                                                      const std::vector<char>& rows) {
  std::vector<std::pair<double, double>> range(
      s.joints(),
      {std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()});
  for (Eigen::Index k = 0; k < s.size(); ++k) {
    const auto i = static_cast<std::size_t>(k);
    if (!s.valid[i] || (!rows.empty() && !rows[i])) continue;
    for (int j = 0; j < s.joints(); ++j) {
      range[j].first = std::min(range[j].first, s.q(k, j));
      range[j].second = std::max(range[j].second, s.q(k, j));
    }
  }
  return range;
}

}  // namespace tpf::offline
