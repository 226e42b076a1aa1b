// Contact-detection metrics against ground truth: latency, smallest force, false alarms.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace tpf::offline {

/// One ground-truth contact: rows [first, last] where gt_contact ≠ 0. (Not the simulator's
/// ContactEvent, a scripted push: one name for two types broke the one-definition rule.)
struct ContactSpan {
  Eigen::Index first = 0;
  Eigen::Index last = 0;
  double peak_force = 0.0;  ///< max |F| [N] over the event
};

/// The events of a log: maximal runs of rows with contact[k] ≠ 0 (NaN counts as no contact);
/// `force` is T × 3 (N).
std::vector<ContactSpan> contact_events(const Eigen::VectorXd& contact,
                                        const Eigen::MatrixXd& force);

/// How one detector did on a set of events.
struct DetectionStats {
  int events = 0;
  int detected = 0;                       ///< events with a detection inside [first, last]
  Eigen::VectorXd latency_s;              ///< per detected event: t(first detection) − t(first)
  Eigen::VectorXd force_at_detection;     ///< |F| at that row [N]
  double median_latency_s = 0.0;          ///< NaN when nothing was detected
  double median_force_n = 0.0;            ///< median |F| at detection
  double smallest_detected_peak_n = 0.0;  ///< smallest event peak force that was detected
  double largest_missed_peak_n = 0.0;     ///< largest event peak force that was missed (0: none)
  /// Share of contact-free rows (outside every event and `settle_s` after its end) on which the
  /// detector fired.
  double false_alarm_share = 0.0;
};

/// Scores `detected` (T, nonzero = the detector says contact) against `events`.
/// Throws tpf::Error on inconsistent sizes.
DetectionStats detection_stats(const Eigen::VectorXd& t, const std::vector<ContactSpan>& events,
                               const Eigen::MatrixXd& force, const Eigen::VectorXi& detected,
                               double settle_s = 0.5);

}  // namespace tpf::offline
