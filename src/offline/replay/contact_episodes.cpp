#include "offline/replay/contact_episodes.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "tpf/common/error.hpp"

namespace tpf::offline {

namespace {

/// Row ranges [first, last] of the runs in contact (NaN rows continue the state before them).
std::vector<std::pair<Eigen::Index, Eigen::Index>> contact_runs(const Eigen::VectorXd& contact) {
  std::vector<std::pair<Eigen::Index, Eigen::Index>> runs;
  bool in = false;
  for (Eigen::Index r = 0; r < contact.size(); ++r) {
    if (!std::isfinite(contact[r])) continue;
    const bool now = contact[r] != 0.0;
    if (now && !in) runs.emplace_back(r, r);
    if (now) runs.back().second = r;
    in = now;
  }
  return runs;
}

/// The episode of rows [first, last]: its times, peaks and joints.
ContactEpisode episode_of(const Eigen::VectorXd& t, const Eigen::MatrixXd& torque,
                          const Eigen::VectorXd& threshold, Eigen::Index first, Eigen::Index last) {
  ContactEpisode e;
  e.start_s = t[first];
  // The first row out of contact after the run (its last row when the log ends in contact).
  Eigen::Index out = last + 1;
  e.end_s = out < t.size() ? t[out] : t[last];
  e.peak_abs_torque = Eigen::VectorXd::Zero(torque.cols());
  for (Eigen::Index r = first; r <= last; ++r)
    for (Eigen::Index j = 0; j < torque.cols(); ++j)
      if (std::isfinite(torque(r, j)))
        e.peak_abs_torque[j] = std::max(e.peak_abs_torque[j], std::abs(torque(r, j)));
  for (Eigen::Index j = 0; j < torque.cols(); ++j)
    if (e.peak_abs_torque[j] > threshold[j]) e.joints.push_back(static_cast<int>(j));
  return e;
}

}  // namespace

std::vector<ContactEpisode> contact_episodes(const Eigen::VectorXd& t,
                                             const Eigen::VectorXd& contact,
                                             const Eigen::MatrixXd& torque,
                                             const Eigen::VectorXd& joint_threshold,
                                             double merge_gap_s) {
  if (contact.size() != t.size() || torque.rows() != t.size() ||
      joint_threshold.size() != torque.cols())
    throw Error("contact_episodes: " + std::to_string(t.size()) + " times, " +
                std::to_string(contact.size()) + " contact flags, " +
                std::to_string(torque.rows()) + " × " + std::to_string(torque.cols()) +
                " torques and " + std::to_string(joint_threshold.size()) + " thresholds");
  std::vector<std::pair<Eigen::Index, Eigen::Index>> merged;
  for (const auto& run : contact_runs(contact)) {
    if (!merged.empty() && t[run.first] - t[merged.back().second + 1] < merge_gap_s)
      merged.back().second = run.second;
    else
      merged.push_back(run);
  }
  std::vector<ContactEpisode> episodes;
  for (const auto& [first, last] : merged)
    episodes.push_back(episode_of(t, torque, joint_threshold, first, last));
  return episodes;
}

}  // namespace tpf::offline
