// Contact episodes of a log: the runs of cycles in which contact was believed (the estimator's
// est_contact, or the ground truth's gt_contact), with the torque they put on each joint.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace tpf::offline {

/// One contact, from its first cycle in contact to the first cycle out of it.
struct ContactEpisode {
  double start_s = 0.0;  ///< t of the first cycle in contact [s]
  /// t of the first cycle out of contact after it (the log's last t when it ends in contact) [s]
  double end_s = 0.0;
  Eigen::VectorXd peak_abs_torque;  ///< per joint: max |τ̂_ext| over the episode [N·m]
  /// Joints (0-based) whose peak exceeds their threshold (contact_episodes), ascending.
  std::vector<int> joints;
};

/// The episodes of `contact` (per row: nonzero in contact, 0 out of it, NaN no answer — a skipped
/// cycle continues the state before it) over times `t` [s]: maximal runs of rows in contact;
/// episodes separated by less than `merge_gap_s` become one. Each episode's per-joint peak
/// |torque| is taken over its rows (finite values of the T × N `torque`), and joint j belongs
/// to it when that peak exceeds `joint_threshold[j]` [N·m] (e.g. the static dead band: the
/// smallest torque the estimator tells from noise). Throws tpf::Error when the sizes differ.
std::vector<ContactEpisode> contact_episodes(const Eigen::VectorXd& t,
                                             const Eigen::VectorXd& contact,
                                             const Eigen::MatrixXd& torque,
                                             const Eigen::VectorXd& joint_threshold,
                                             double merge_gap_s = 0.0);

}  // namespace tpf::offline
