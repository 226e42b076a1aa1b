#include "offline/measured_study/measured_facts.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

#include "core/common/unoptimised_when_sanitized.hpp"
#include "offline/log/torque_sensor.hpp"
#include "offline/report/text_format.hpp"

namespace tpf::offline {
namespace {

/// Sign changes of v between stretches where |v| ≥ threshold.
int count_velocity_reversals(const Eigen::Ref<const Eigen::VectorXd>& v, double threshold) {
  int reversals = 0;
  double last = 0.0;
  for (Eigen::Index k = 0; k < v.size(); ++k) {
    if (!std::isfinite(v[k]) || std::abs(v[k]) < threshold) continue;
    const double sign = v[k] > 0 ? 1.0 : -1.0;
    if (last != 0.0 && sign != last) ++reversals;
    last = sign;
  }
  return reversals;
}

double positive_velocity_share(const Eigen::Ref<const Eigen::VectorXd>& v, double threshold) {
  double positive = 0, moving = 0;
  for (Eigen::Index k = 0; k < v.size(); ++k)
    if (std::isfinite(v[k]) && std::abs(v[k]) >= threshold) {
      ++moving;
      positive += v[k] > 0;
    }
  return moving > 0 ? positive / moving : std::nan("");
}

MeasuredFile one_file_facts(const Log& log, const JointSamples& s, std::size_t f,
                            const std::vector<std::vector<SensorColumn>>& sensors,
                            const MeasuredFactsOptions& o) {
  const auto [begin, end] = log.file_rows(f);
  MeasuredFile file;
  file.name = std::filesystem::path(log.file_path(f)).filename().string();
  file.samples = end - begin;
  file.seconds = end > begin ? s.t[end - 1] - s.t[begin] : 0.0;
  for (int j = 0; j < s.joints(); ++j) {
    const auto v = s.dq.col(j).segment(begin, end - begin);
    file.reversals.push_back(count_velocity_reversals(v, o.reversal_velocity));
    file.positive_share.push_back(positive_velocity_share(v, o.reversal_velocity));
    file.sensor_usable.push_back(sensor_usable(sensors, f, j));
  }
  return file;
}

/// Σ of squared second differences of x within [begin, end) and their count (finite ones only).
void add_second_differences_of(const Eigen::Ref<const Eigen::VectorXd>& x, double& sum,
                               double& count) {
  for (Eigen::Index k = 1; k + 1 < x.size(); ++k) {
    const double d = x[k + 1] - 2 * x[k] + x[k - 1];
    if (std::isfinite(d)) sum += d * d, ++count;
  }
}

std::string facts_joint_list(const std::vector<int>& joints) {
  std::string text;
  for (std::size_t i = 0; i < joints.size(); ++i)
    text += (i ? ", " : "") + std::to_string(joints[i] + 1);
  return text;
}

}  // namespace

MeasuredFacts measured_facts(const std::vector<LogWithSamples>& logs,
                             const MeasuredFactsOptions& o) {
  MeasuredFacts facts;
  facts.options = o;
  const int joints = logs.empty() ? 0 : logs.front().samples->joints();
  std::vector<double> sum(joints, 0.0), count(joints, 0.0), noisy(joints, 0.0);
  std::vector<double> current2(joints, 0.0), current_n(joints, 0.0), sensor2(joints, 0.0),
      sensor_n(joints, 0.0);
  for (const LogWithSamples& item : logs) {
    const Log& log = *item.log;
    const JointSamples& s = *item.samples;
    const auto sensors = torque_sensor_columns(log, s.joints());
    const std::size_t first = facts.files.size();
    for (std::size_t f = 0; f < log.file_count(); ++f)
      facts.files.push_back(one_file_facts(log, s, f, sensors, o));
    for (RepeatedMotion r : repeated_motions(log, s, o.repeat_tolerance)) {
      r.first += first;
      r.second += first;
      facts.repeats.push_back(r);
    }
    for (std::size_t f = 0; f < log.file_count(); ++f) {
      const auto [begin, end] = log.file_rows(f);
      for (int j = 0; j < joints; ++j) {
        add_second_differences_of(s.effort.col(j).segment(begin, end - begin), current2[j],
                                  current_n[j]);
        if (sensor_usable(sensors, f, j))
          add_second_differences_of(
              log.col(indexed_name("tau_sensor", j + 1)).segment(begin, end - begin), sensor2[j],
              sensor_n[j]);
      }
    }
    for (int j = 0; j < joints; ++j)
      for (Eigen::Index k = 0; k < s.size(); ++k) {
        const double v = std::abs(s.dq(k, j));
        if (!std::isfinite(v) || v >= o.rest_velocity) continue;
        sum[j] += v * v;
        ++count[j];
        noisy[j] += v >= o.static_velocity;
      }
  }
  for (int j = 0; j < joints; ++j) {
    facts.rest_velocity_rms.push_back(count[j] > 0 ? std::sqrt(sum[j] / count[j]) : std::nan(""));
    facts.rest_noise_moving_share.push_back(count[j] > 0 ? noisy[j] / count[j] : std::nan(""));
    facts.current_noise.push_back(current_n[j] > 0 ? std::sqrt(current2[j] / current_n[j] / 6)
                                                   : std::nan(""));
    facts.sensor_noise.push_back(sensor_n[j] > 0 ? std::sqrt(sensor2[j] / sensor_n[j] / 6)
                                                 : std::nan(""));
  }
  return facts;
}

std::vector<double> outside_range_share(const JointSamples& fit, const JointSamples& heldout) {
  std::vector<double> share;
  const std::vector<std::pair<double, double>> range = position_range(fit);
  for (int j = 0; j < fit.joints(); ++j) {
    const auto [lo, hi] = range[j];
    double outside = 0, count = 0;
    for (Eigen::Index k = 0; k < heldout.size(); ++k)
      if (heldout.valid[static_cast<std::size_t>(k)]) {
        ++count;
        outside += heldout.q(k, j) < lo || heldout.q(k, j) > hi;
      }
    share.push_back(count > 0 ? outside / count : std::nan(""));
  }
  return share;
}

TPF_UNOPTIMISED_WHEN_SANITIZED_BEGIN
std::vector<std::string> measured_fact_lines(const MeasuredFacts& facts) {
  std::vector<std::string> lines;
  const MeasuredFactsOptions& o = facts.options;
  double shortest = 1e300, longest = 0;
  int most_reversals = 0;
  for (const MeasuredFile& f : facts.files) {
    shortest = std::min(shortest, f.seconds);
    longest = std::max(longest, f.seconds);
    std::vector<int> none, one_way, flat;
    for (std::size_t j = 0; j < f.reversals.size(); ++j) {
      const int joint = static_cast<int>(j);
      most_reversals = std::max(most_reversals, f.reversals[j]);
      if (f.reversals[j] == 0) none.push_back(joint);
      const double p = f.positive_share[j];
      if (std::isfinite(p) && (p > 0.9 || p < 0.1)) one_way.push_back(joint);
      if (!f.sensor_usable[j]) flat.push_back(joint);
    }
    std::string line = f.name + format_sentence(": %.2f s (%.0f samples)", f.seconds,
                                                static_cast<double>(f.samples));
    line += "; velocity reversals per joint (|q̇| ≥ " +
            format_sentence("%g rad/s", o.reversal_velocity) + "):";
    for (std::size_t j = 0; j < f.reversals.size(); ++j)
      line += (j ? " / " : " ") + std::to_string(f.reversals[j]);
    if (!none.empty())
      line += none.size() == 1 ? "; joint " + facts_joint_list(none) + " never reverses"
                               : "; joints " + facts_joint_list(none) + " never reverse";
    if (!one_way.empty())
      line += (one_way.size() == 1 ? "; joint " + facts_joint_list(one_way) + " moves"
                                   : "; joints " + facts_joint_list(one_way) + " move") +
              " ≥ 90 % of the time in one direction";
    line += flat.empty() ? "; every torque sensor varies"
                         : "; torque sensor flat or missing on joint" +
                               std::string(flat.size() == 1 ? " " : "s ") + facts_joint_list(flat) +
                               " (not scored there)";
    lines.push_back(line + ".");
  }
  lines.push_back(format_sentence("Each file lasts %.1f–%.1f s", shortest, longest) +
                  " and no joint reverses more than " + std::to_string(most_reversals) +
                  " times in a file: Coulomb friction is seen in few direction changes, the "
                  "friction at a reversal (memory, break-away) in a handful of events, and the "
                  "interleaved 5 s blocks of a one-file split hold almost nothing out. Held out "
                  "by file is the only validation these files support.");
  std::string rest = "Velocity at rest (|q̇| < " + format_sentence("%g rad/s", o.rest_velocity) +
                     "), RMS per joint [rad/s]:";
  double worst_share = 0;
  for (std::size_t j = 0; j < facts.rest_velocity_rms.size(); ++j) {
    rest += (j ? " / " : " ") + format_sentence("%.2g", facts.rest_velocity_rms[j]);
    if (std::isfinite(facts.rest_noise_moving_share[j]))
      worst_share = std::max(worst_share, facts.rest_noise_moving_share[j]);
  }
  rest += format_sentence(
              "; up to %.0f %% of those samples are at or above the static threshold %g rad/s",
              100 * worst_share, o.static_velocity) +
          ", so the Stribeck model takes the noise's sign and predicts full Coulomb friction at "
          "rest, where the drive holds whatever friction it stopped with: the gain is decided "
          "in motion only.";
  lines.push_back(rest);
  if (!facts.current_noise.empty()) {
    std::string line =
        "Sample-to-sample noise σ per joint [N·m] (second differences within each "
        "file, as white noise), K_t·i vs τ_sensor:";
    for (std::size_t j = 0; j < facts.current_noise.size(); ++j)
      line += (j ? " / " : " ") + format_sentence("%.2f vs ", facts.current_noise[j]) +
              (std::isfinite(facts.sensor_noise[j]) ? format_sentence("%.3f", facts.sensor_noise[j])
                                                    : std::string("– (flat)"));
    lines.push_back(line +
                    ". The published sensor is far smoother than the current (filtered, or "
                    "partly computed: the files cannot tell), so an unfiltered current-based "
                    "torque keeps about σ of error against it whatever the model.");
  }
  if (!facts.outside_share.empty()) {
    std::string line =
        "Share of the held-out samples where q lies outside the fitting files' range "
        "of q, per joint:";
    for (std::size_t j = 0; j < facts.outside_share.size(); ++j)
      line += (j ? " / " : " ") + format_sentence("%.0f %%", 100 * facts.outside_share[j]);
    lines.push_back(line +
                    ". A model of q (the rigid body, a position ripple, a compensator that sees "
                    "q) extrapolates there, so the measured compensator does not see q; the "
                    "compensator's domain at run time bounds q̇ and q̈, not q.");
  }
  for (const RepeatedMotion& r : facts.repeats) {
    std::string line =
        facts.files[r.second].name + " repeats the motion of " + facts.files[r.first].name +
        format_sentence(" (|Δq| ≤ %.3g rad), yet K_t·i differs by", r.max_position_difference) +
        " (RMS per joint, N·m)";
    for (std::size_t j = 0; j < r.torque_rms_difference.size(); ++j)
      line += (j ? " / " : " ") + format_sentence("%.2f", r.torque_rms_difference[j]);
    line +=
        ": the same motion does not give the same current from run to run (the current's "
        "sample noise σ above accounts for √2·σ of it), and a file that repeats another is no "
        "independent held-out file.";
    lines.push_back(line);
  }
  return lines;
}
TPF_UNOPTIMISED_WHEN_SANITIZED_END

}  // namespace tpf::offline
