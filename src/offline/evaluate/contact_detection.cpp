#include "offline/evaluate/contact_detection.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "tpf/common/error.hpp"

namespace tpf::offline {
namespace {

double median(Eigen::VectorXd v) {
  if (v.size() == 0) return std::numeric_limits<double>::quiet_NaN();
  std::sort(v.begin(), v.end());
  const Eigen::Index n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace

std::vector<ContactSpan> contact_events(const Eigen::VectorXd& contact,
                                        const Eigen::MatrixXd& force) {
  if (force.rows() != contact.size() || force.cols() != 3)
    throw Error::at("contact events", 0, "force", "must be T × 3 like the contact column");
  std::vector<ContactSpan> events;
  for (Eigen::Index k = 0; k < contact.size(); ++k) {
    const bool on = std::isfinite(contact[k]) && contact[k] != 0.0;
    const bool was_on = k > 0 && std::isfinite(contact[k - 1]) && contact[k - 1] != 0.0;
    if (on && !was_on) events.push_back({k, k, 0.0});
    if (on) {
      ContactSpan& e = events.back();
      e.last = k;
      const double f = force.row(k).norm();
      if (std::isfinite(f)) e.peak_force = std::max(e.peak_force, f);
    }
  }
  return events;
}

DetectionStats detection_stats(const Eigen::VectorXd& t, const std::vector<ContactSpan>& events,
                               const Eigen::MatrixXd& force, const Eigen::VectorXi& detected,
                               double settle_s) {
  if (detected.size() != t.size() || force.rows() != t.size())
    throw Error::at("detection", 0, "detected", "sizes disagree with t");
  DetectionStats s;
  s.events = static_cast<int>(events.size());
  std::vector<double> latency, at_detection;
  s.smallest_detected_peak_n = std::numeric_limits<double>::quiet_NaN();
  Eigen::VectorXi excluded = Eigen::VectorXi::Zero(t.size());
  for (const ContactSpan& e : events) {
    Eigen::Index end = e.last;
    while (end + 1 < t.size() && !(t[end + 1] - t[e.last] > settle_s))
      ++end;
    excluded.segment(e.first, end - e.first + 1).setOnes();
    Eigen::Index hit = -1;
    for (Eigen::Index k = e.first; k <= e.last && hit < 0; ++k)
      if (detected[k] != 0 && std::isfinite(t[k])) hit = k;
    if (hit < 0) {
      s.largest_missed_peak_n = std::max(s.largest_missed_peak_n, e.peak_force);
      continue;
    }
    ++s.detected;
    latency.push_back(t[hit] - t[e.first]);
    at_detection.push_back(force.row(hit).norm());
    if (!(e.peak_force >= s.smallest_detected_peak_n)) s.smallest_detected_peak_n = e.peak_force;
  }
  s.latency_s =
      Eigen::Map<Eigen::VectorXd>(latency.data(), static_cast<Eigen::Index>(latency.size()));
  s.force_at_detection = Eigen::Map<Eigen::VectorXd>(
      at_detection.data(), static_cast<Eigen::Index>(at_detection.size()));
  s.median_latency_s = median(s.latency_s);
  s.median_force_n = median(s.force_at_detection);
  long free_rows = 0, alarms = 0;
  for (Eigen::Index k = 0; k < t.size(); ++k) {
    if (excluded[k] || !std::isfinite(t[k])) continue;
    ++free_rows;
    if (detected[k] != 0) ++alarms;
  }
  s.false_alarm_share = free_rows ? double(alarms) / double(free_rows) : 0.0;
  return s;
}

}  // namespace tpf::offline
