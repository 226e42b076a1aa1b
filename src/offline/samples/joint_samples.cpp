#include "offline/samples/joint_samples.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <initializer_list>

#include "offline/fit/parallel_halves.hpp"
#include "offline/samples/held_out_rows.hpp"
#include "offline/signal/acceleration.hpp"
#include "offline/signal/segments.hpp"
#include "tpf/common/error.hpp"

namespace tpf::offline {

bool identification_column(std::string_view name) {
  if (name == "t") return true;
  const std::size_t digits = name.find_first_of("0123456789");
  if (digits == 0 || digits == std::string_view::npos ||
      name.find_first_not_of("0123456789", digits) != std::string_view::npos)
    return false;
  const std::string_view prefix = name.substr(0, digits);
  for (const std::string_view read : {"q", "dq", "ddq", "i", "tau", "temp", "tau_sensor"})
    if (prefix == read) return true;
  return false;
}

bool holds_rows_out(const JointSamples& samples) {
  return std::any_of(samples.heldout.begin(), samples.heldout.end(),
                     [](char held) { return held != 0; });
}

std::vector<Eigen::Index> moving_training_rows(const JointSamples& s, int j, std::size_t most) {
  std::vector<Eigen::Index> moving;
  for (Eigen::Index k = 0; k < s.size(); ++k)
    if (s.valid[k] && !s.heldout[k] && s.regimes[j][k] == Regime::Moving) moving.push_back(k);
  if (most == 0 || moving.size() <= most) return moving;
  const std::size_t stride = moving.size() / most;
  std::vector<Eigen::Index> strided;
  for (std::size_t i = 0; i < moving.size(); i += stride)
    strided.push_back(moving[i]);
  return strided;
}

std::string nothing_held_out_note(const JointSamples& s, const SampleOptions& options) {
  if (!options.hold_out) return {};
  for (Eigen::Index k = 0; k < s.size(); ++k)
    if (s.valid[static_cast<std::size_t>(k)] && s.heldout[static_cast<std::size_t>(k)]) return {};
  const double span = s.size() > 0 ? s.t[s.size() - 1] - s.t[0] : 0.0;
  char text[512];
  std::snprintf(text, sizeof text,
                "nothing is held out: a one-file log holds out one block of %.3g s in every %d, "
                "the first from %.3g s on, and this log spans %.3g s, so every held-out figure is "
                "NaN and nothing can be judged on held-out data. Pass a log of at least %.3g s, or "
                "several --log (the last file is held out), or score the written model on another "
                "log with tpf validate",
                options.block_s, options.heldout_every,
                options.block_s * (options.heldout_every - 1), span,
                options.block_s * options.heldout_every);
  return text;
}

namespace {

/// Sign of joint j's last motion, reset at gaps and NaNs (a new segment starts unknown).
void hold_motion_sign(const std::vector<Segment>& segments, const RegimeOptions& regimes, int j,
                      JointSamples& s) {
  s.held_sign.col(j).setZero();  // outside every segment (t not finite)
  for (const Segment& seg : segments) {
    double sign = 0.0;
    for (Eigen::Index k = seg.begin; k < seg.end; ++k) {
      const double v = s.dq(k, j);
      if (!std::isfinite(v)) {
        sign = 0.0;
      } else if (std::abs(v) >= regimes.static_velocity) {
        sign = v > 0 ? 1.0 : -1.0;
      }
      s.held_sign(k, j) = sign;
    }
  }
}

/// Column j - 1 (joint j) of q, dq, effort, ddq (read or derived), temperature, the regimes and
/// the held sign of motion.
void extract_joint(const Log& log, const std::string& prefix, bool has_temperature,
                   const SampleOptions& options, double step, const std::vector<Segment>& segments,
                   int j, JointSamples& s) {
  s.q.col(j - 1) = log.col(indexed_name("q", j));
  s.dq.col(j - 1) = log.col(indexed_name("dq", j));
  s.effort.col(j - 1) = log.col(indexed_name(prefix, j)) * s.units.newton_metres_per_unit(j - 1);
  const std::string acc = indexed_name("ddq", j);
  s.ddq.col(j - 1) = log.has(acc) ? Eigen::VectorXd(log.col(acc))
                                  : derive_acceleration(s.t, s.dq.col(j - 1),
                                                        options.acceleration_cutoff_hz, step);
  if (has_temperature) s.temperature.col(j - 1) = log.col(indexed_name("temp", j));
  s.regimes[j - 1] = label_regimes(s.t, s.dq.col(j - 1), options.regimes);
  hold_motion_sign(segments, options.regimes, j - 1, s);
}

}  // namespace

JointSamples extract_joint_samples(const Log& log, const Eigen::VectorXd& torque_constant,
                                   const SampleOptions& options) {
  JointSamples s;
  s.source = log.source;
  const int n_joints = log.joint_count();
  if (n_joints < 1) throw Error::at(log.source, 0, "q1", "the log has no joint columns");
  if (torque_constant.size() != n_joints)
    throw Error::at(log.source, 0, "",
                    "the log has " + std::to_string(n_joints) + " joints, the robot file " +
                        std::to_string(torque_constant.size()));
  const std::string prefix = log.effort_prefix();
  s.units = {effort_unit_of_column(prefix), torque_constant};
  s.simulated = log.meta.get("source").value_or("").find("simulated") != std::string::npos;
  const Eigen::Index n = log.rows();
  s.t = log.col("t");
  s.q.resize(n, n_joints);
  s.dq.resize(n, n_joints);
  s.ddq.resize(n, n_joints);
  s.effort.resize(n, n_joints);
  bool has_temperature = true;
  for (int j = 1; j <= n_joints; ++j)
    has_temperature = has_temperature && log.has(indexed_name("temp", j));
  if (has_temperature) s.temperature.resize(n, n_joints);
  s.regimes.resize(n_joints);
  s.held_sign.resize(n, n_joints);
  const double step = median_step(s.t);  // once for every joint's filters and segments
  if (!(step > 0))
    throw Error::at(log.source, 0, "t",
                    n < 2 ? "the log has " + std::to_string(n) +
                                " row(s): a time step needs at least two, and a fit far more"
                          : "the time column does not advance (its median step is not positive)");
  const std::vector<Segment> segments =
      contiguous_segments(s.t, {}, options.regimes.gap_factor, step);  // of t alone
  // Joints are independent columns: half of them on a helper thread (same result as serial).
  parallel_halves(n_joints, [&](Eigen::Index first, Eigen::Index last) {
    for (int j = static_cast<int>(first) + 1; j <= last; ++j)
      extract_joint(log, prefix, has_temperature, options, step, segments, j, s);
  });

  s.valid.assign(n, 1);
  for (Eigen::Index k = 0; k < n; ++k) {
    bool ok = std::isfinite(s.t[k]) && s.q.row(k).allFinite() && s.dq.row(k).allFinite() &&
              s.ddq.row(k).allFinite() && s.effort.row(k).allFinite();
    if (has_temperature) ok = ok && s.temperature.row(k).allFinite();
    const auto plausible = [](const auto& row) {
      return (row.array().abs() <= kImplausibleValue).all();
    };
    const bool in_range = plausible(s.q.row(k)) && plausible(s.dq.row(k)) &&
                          plausible(s.ddq.row(k)) && plausible(s.effort.row(k)) &&
                          (!has_temperature || plausible(s.temperature.row(k)));
    s.out_of_range_count += ok && !in_range;
    s.valid[k] = ok && in_range;
    s.invalid_count += !s.valid[k];
  }
  if (n - static_cast<Eigen::Index>(s.invalid_count) < 100)
    throw Error::at(log.source, 0, "",
                    "fewer than 100 complete samples (" +
                        std::to_string(n - static_cast<Eigen::Index>(s.invalid_count)) +
                        "): nothing to identify from");

  decide_held_out_rows(log, options, s);
  return s;
}

std::string skipped_samples_text(const JointSamples& samples) {
  const std::size_t missing = samples.invalid_count - samples.out_of_range_count;
  std::string text = std::to_string(missing) +
                     " skipped for a missing value (in the log, or q̈ not derivable at a gap or an "
                     "end)";
  if (samples.out_of_range_count > 0) {
    char printed[32];
    std::snprintf(printed, sizeof printed, "%g", kImplausibleValue);
    std::string limit = printed;  // "1e+09" → "1e9"
    if (const std::size_t e = limit.find("e+"); e != std::string::npos)
      limit.erase(e + 1, limit.find_first_not_of("+0", e + 1) - (e + 1));
    text += ", " + std::to_string(samples.out_of_range_count) + " for a value beyond ±" + limit +
            " (no arm's q, q̇, q̈ or effort: a corrupt field?)";
  }
  return text;
}

}  // namespace tpf::offline
