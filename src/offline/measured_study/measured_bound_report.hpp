// The measured report's section on what bounds the held-out error (MeasuredBound): a table per
// split, the verdict per joint, and the drive loss against q̇ on the fitting and scored files.
#pragma once

#include <string>
#include <vector>

#include "offline/measured_study/measured_bound.hpp"
#include "offline/report/html_report.hpp"

namespace tpf::offline {

/// Per joint of `b` with a scored sensor: why the target is met or missed, from its numbers.
std::string measured_bound_verdict(const MeasuredBound& b, int joint);

/// The verdicts of every joint that misses the target, forward split first (a split without a
/// maker RMSE has none).
std::vector<std::string> measured_bound_verdicts(const MeasuredBound& forward,
                                                 const MeasuredBound& reverse);

/// The section: both splits' tables and verdicts, and a figure for each joint that misses the
/// target on either split. `reverse` may be empty (no maker RMSE).
void add_measured_bound_section(HtmlReport& page, const MeasuredBound& forward,
                                const MeasuredBound& reverse);

/// Every number of `b` as JSON text (an object; NaN as null).
std::string measured_bound_json(const MeasuredBound& b);

}  // namespace tpf::offline
