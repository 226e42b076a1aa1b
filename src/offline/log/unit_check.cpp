#include "offline/log/unit_check.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <set>

#include "offline/log/log_text.hpp"

namespace tpf::offline {
namespace {

std::string joint_name(int j) {
  return "joint " + std::to_string(j + 1);
}

/// A factor by which a wrongly read column differs from the right one, and the question it asks.
struct Reading {
  double factor;
  std::string question;
};

/// The readings that would make the right effort `factor` times what it is.
std::vector<Reading> effort_readings(const UnitCheckView& in, int j) {
  const double r = std::abs(in.gear_ratio[j]);
  const double kt = std::abs(in.torque_constant[j]);
  std::vector<Reading> out = {
      {-1.0, "is the effort's sign reversed?"},
      {1000.0, "is the effort 1000x too large (a current in A read as mA, or N*m as mN*m)?"},
      {1e-3, "is the effort 1000x too small (a current in mA read as A, or mN*m as N*m)?"},
      {1.0 / r, "is the effort motor-side torque (not taken through the gear ratio " +
                    log_text::printed("%.4g", r) + ")?"},
      {r, "is the effort joint torque taken through the gear ratio " +
              log_text::printed("%.4g", r) + " as if it were motor torque?"}};
  out.push_back({kt, "is the effort a joint torque in N*m read as a current in A (x K_t " +
                         log_text::printed("%.4g", kt) + ")?"});
  out.push_back(
      {kt / r, "is the effort a motor torque in N*m read as a current in A (x K_t/ratio " +
                   log_text::printed("%.4g", kt / r) + ")?"});
  out.push_back({1.0 / kt, "is the effort a current in A read as a joint torque in N*m?"});
  out.push_back({r / kt, "is the effort a current in A read as a motor torque in N*m?"});
  if (r != 1.0) out.push_back({r * 1000.0, "is the effort motor torque in mN*m?"});
  const std::size_t n = out.size();
  for (std::size_t k = 1; k < n; ++k)  // each also with the sign reversed
    out.push_back({-out[k].factor, out[k].question + " (and its sign reversed)"});
  return out;
}

/// The reading within ×/÷ tolerance of `factor`, or an empty question.
std::string matching_reading(const std::vector<Reading>& readings, double factor,
                             double tolerance) {
  for (const Reading& r : readings)
    if (r.factor * factor > 0 && std::abs(std::log(factor / r.factor)) < std::log(tolerance))
      return r.question;
  return {};
}

bool joint_is_prismatic(const UnitCheckView& in, int j) {
  return static_cast<std::size_t>(j) < in.prismatic.size() &&
         in.prismatic[static_cast<std::size_t>(j)];
}

/// Joint j's rest, rest-acceleration and moving thresholds (rad or m).
std::array<double, 3> joint_thresholds(const UnitCheckView& in, const UnitCheckOptions& o, int j) {
  if (joint_is_prismatic(in, j))
    return {o.rest_linear_velocity, o.rest_linear_acceleration, o.moving_linear_velocity};
  return {o.rest_velocity, o.rest_acceleration, o.moving_velocity};
}

/// Rows where every joint's |q̇| and |q̈| are below its rest thresholds and every value is finite.
std::vector<Eigen::Index> rest_rows(const UnitCheckView& in, const UnitCheckOptions& o) {
  std::vector<Eigen::Index> rows;
  const int joints = static_cast<int>(in.q.cols());
  std::vector<std::array<double, 3>> limits;
  for (int j = 0; j < joints; ++j)
    limits.push_back(joint_thresholds(in, o, j));
  for (Eigen::Index r = 0; r < in.q.rows(); ++r) {
    // The thresholds first (a NaN q̇ or q̈ fails them), then every value finite.
    bool rests = true;
    for (int j = 0; rests && j < joints; ++j)
      rests = std::abs(in.dq(r, j)) < limits[static_cast<std::size_t>(j)][0] &&
              std::abs(in.ddq(r, j)) < limits[static_cast<std::size_t>(j)][1];
    rests = rests && in.q.row(r).allFinite() && in.dq.row(r).allFinite() &&
            in.ddq.row(r).allFinite() && in.effort.row(r).allFinite() &&
            in.gravity.row(r).allFinite();
    if (rests) rows.push_back(r);
  }
  return rows;
}

void check_rest(const UnitCheckView& in, const UnitCheckOptions& o, LogChecks& out) {
  const std::vector<Eigen::Index> rows = rest_rows(in, o);
  for (int j = 0; j < in.q.cols(); ++j) {
    if (std::find(out.dead_joints.begin(), out.dead_joints.end(), j + 1) != out.dead_joints.end())
      continue;
    double largest = 0.0;
    for (Eigen::Index r = 0; r < in.gravity.rows(); ++r)
      if (std::isfinite(in.gravity(r, j))) largest = std::max(largest, std::abs(in.gravity(r, j)));
    const double least = std::max(o.min_gravity, o.min_gravity_share * largest);
    double tg = 0, gg = 0;
    std::size_t used = 0;
    for (const Eigen::Index r : rows)
      if (std::abs(in.gravity(r, j)) >= least) {
        tg += in.effort(r, j) * in.gravity(r, j);
        gg += in.gravity(r, j) * in.gravity(r, j);
        ++used;
      }
    if (used < o.min_rest_samples) {
      out.notes.push_back(joint_name(j) +
                          ": effort against gravity not checked: " + std::to_string(used) +
                          " samples at rest (|dq| < " + log_text::printed("%.3g", o.rest_velocity) +
                          " rad/s, |ddq| < " + log_text::printed("%.3g", o.rest_acceleration) +
                          " rad/s^2 on every joint) with a " + "gravity torque of at least " +
                          log_text::printed("%.3g", least) + " N*m (" +
                          log_text::printed("%.0f", 100 * o.min_gravity_share) +
                          " % of its largest), " + std::to_string(o.min_rest_samples) + " needed");
      continue;
    }
    const double f = tg / gg;
    out.rest_factor[static_cast<std::size_t>(j)] = f;
    double off = 0, effort = 0;
    for (const Eigen::Index r : rows)
      if (std::abs(in.gravity(r, j)) >= least) {
        off += std::pow(in.effort(r, j) - f * in.gravity(r, j), 2);
        effort += in.effort(r, j) * in.effort(r, j);
      }
    const double misfit = std::sqrt(off / effort);
    if (f >= 1.0 / o.fitting_factor && f <= o.fitting_factor && misfit <= o.rest_misfit) continue;
    if (f >= 1.0 / o.fitting_factor && f <= o.fitting_factor) {
      out.problems.push_back(joint_name(j) + ": the effort at rest does not follow the robot " +
                             "file's gravity torque (" + log_text::printed("%.0f", 100 * misfit) +
                             " % RMS off its best multiple, " + std::to_string(used) +
                             " samples at rest): are q's units, sign and zero right?");
      continue;
    }
    const std::string reading = matching_reading(effort_readings(in, j), f, o.reading_tolerance);
    out.problems.push_back(
        joint_name(j) + " rests at " + log_text::printed("%.3g", f) +
        "x the robot file's gravity torque (" + std::to_string(used) + " samples at rest): " +
        (reading.empty() ? std::string("no single factor explains it; are q's units and zero, "
                                       "and the effort's kind, right?")
                         : reading));
  }
}

void check_dead_channels(const UnitCheckView& in, const UnitCheckOptions& o, LogChecks& out) {
  for (int j = 0; j < in.effort.cols(); ++j) {
    std::set<double> distinct;
    std::size_t finite = 0, zeros = 0;
    for (Eigen::Index r = 0; r < in.effort.rows(); ++r) {
      const double e = in.effort(r, j);
      if (!std::isfinite(e)) continue;
      ++finite;
      zeros += e == 0.0 ? 1 : 0;
      if (distinct.size() <= o.dead_distinct_values) distinct.insert(e);
    }
    if (finite == 0) continue;
    const double zero_share = static_cast<double>(zeros) / static_cast<double>(finite);
    // a joint that rests all along may well hold few values (a steady current's counts)
    const bool moves = (in.dq.col(j).array().abs() > joint_thresholds(in, o, j)[2]).count() > 0;
    const bool few = moves && distinct.size() <= o.dead_distinct_values;
    if (zero_share < o.dead_zero_fraction && !few) continue;
    out.dead_joints.push_back(j + 1);
    out.problems.push_back(joint_name(j) + ": dead effort channel: exactly 0 in " +
                           log_text::printed("%.0f", 100.0 * zero_share) + " % of " +
                           std::to_string(finite) + " samples, " +
                           (few ? std::to_string(distinct.size())
                                : "more than " + std::to_string(o.dead_distinct_values)) +
                           " distinct values" + (few ? " while the joint moves" : "") +
                           "; claims that need its effort leave it out");
  }
}

void check_limits(const UnitCheckView& in, const UnitCheckOptions& o, LogChecks& out) {
  for (int j = 0; j < in.q.cols(); ++j) {
    if (!std::isfinite(in.lower[j]) || !std::isfinite(in.upper[j])) continue;
    std::size_t outside = 0, finite = 0;
    double worst = 0.0;
    for (Eigen::Index r = 0; r < in.q.rows(); ++r) {
      const double q = in.q(r, j);
      if (!std::isfinite(q)) continue;
      ++finite;
      const double beyond = std::max(in.lower[j] - q, q - in.upper[j]);
      if (beyond > o.limit_margin) ++outside;
      worst = std::max(worst, beyond);
    }
    if (outside == 0) continue;
    const std::string unit = joint_is_prismatic(in, j) ? " m" : " rad";
    out.problems.push_back(joint_name(j) + ": q outside the robot file's limits [" +
                           log_text::printed("%.4g", in.lower[j]) + ", " +
                           log_text::printed("%.4g", in.upper[j]) + "]" + unit + " in " +
                           std::to_string(outside) + " of " + std::to_string(finite) +
                           " samples (up to " + log_text::printed("%.4g", worst) + unit +
                           " beyond): are q's units, sign and zero right?");
  }
}

/// q̇ against the central difference of q over samples that move.
void check_velocity(const UnitCheckView& in, const UnitCheckOptions& o, LogChecks& out) {
  for (int j = 0; j < in.q.cols(); ++j) {
    double vd = 0, dd = 0;
    for (Eigen::Index r = 1; r + 1 < in.q.rows(); ++r) {
      const double step = in.t[r + 1] - in.t[r - 1];
      const double d = (in.q(r + 1, j) - in.q(r - 1, j)) / step;
      if (!std::isfinite(d) || !std::isfinite(in.dq(r, j)) ||
          std::abs(d) < joint_thresholds(in, o, j)[0])
        continue;
      vd += in.dq(r, j) * d;
      dd += d * d;
    }
    if (!(dd > 0)) continue;
    const double f = vd / dd;
    if (f >= 0.8 && f <= 1.25) continue;
    const double r = std::abs(in.gear_ratio[j]);
    const double deg = 180.0 / std::numbers::pi;
    const std::vector<Reading> readings = {
        {-1.0, "is the sign of q or of dq reversed?"},
        {deg, "is q in radians and dq in degrees per second (or q read as degrees)?"},
        {1.0 / deg, "is q in degrees and dq in radians per second?"},
        {r, "is dq motor-side (not through the gear ratio " + log_text::printed("%.4g", r) + ")?"},
        {1.0 / r,
         "is q motor-side (not through the gear ratio " + log_text::printed("%.4g", r) + ")?"}};
    const std::string reading = matching_reading(readings, f, o.reading_tolerance);
    out.problems.push_back(
        joint_name(j) + ": dq is " + log_text::printed("%.3g", f) +
        "x the difference quotient of q: " +
        (reading.empty() ? std::string("are their units and time right?") : reading));
  }
}

}  // namespace

LogChecks check_log_units(const UnitCheckInput& in, const UnitCheckOptions& options) {
  return check_log_units(
      UnitCheckView{in.t, in.q, in.dq, in.ddq, in.effort, in.gravity, in.gear_ratio,
                    in.torque_constant, in.effort_is_current, in.lower, in.upper, in.prismatic},
      options);
}

LogChecks check_log_units(const UnitCheckView& in, const UnitCheckOptions& options) {
  LogChecks out;
  out.rest_factor.assign(static_cast<std::size_t>(in.q.cols()), std::nan(""));
  check_dead_channels(in, options, out);
  check_rest(in, options, out);
  check_limits(in, options, out);
  check_velocity(in, options, out);
  return out;
}

}  // namespace tpf::offline
