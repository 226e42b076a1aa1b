// The measured loop's report: measured.html (MEASURED banner, the data's attribution), the
// numbers as measured.json, and the summary the demo's index page and terminal show.
#pragma once

#include <filesystem>
#include <string>

#include "offline/measured_study/measured_pipeline.hpp"
#include "offline/report/html_report.hpp"

namespace tpf::offline {

/// True when `rmse` is at least `target` (a share) below the maker's RMSE on the same samples.
bool meets_target(double maker, double rmse, double target);

/// Per joint: RMSE of every column of a split [N·m] with its change against the maker, and
/// which columns meet the target.
Table measured_table(const MeasuredSplit& split, double target);

/// diagnose's written effects one by one against the held-out files' effort (mA).
Table diagnosis_effort_table(const MeasuredResult& result);

/// Which of diagnose's written effects lower the held-out files' current error and which raise it.
std::string diagnosis_transfer_sentence(const MeasuredResult& result);

/// The candidates tested against the sensor: held-out change per joint, claimed or not.
Table candidate_table(const MeasuredResult& result);

/// Per joint: the best memoryless model, the compensator against it, the compensator target and
/// the noise floor (MeasuredFloor, its target) with the most any model of the motion could gain.
Table compensator_floor_table(const MeasuredFloor& floor);

/// Joints (1-based) on which the floor leaves room for the compensator target, as a sentence.
std::string compensator_floor_sentence(const MeasuredFloor& floor);

/// What the sensor-fitted friction and the current low-pass columns are, with the time constants
/// chosen.
std::string low_pass_sentence(const MeasuredResult& result);

/// The candidates claimed (with their joints) and those supported nowhere, in one sentence.
std::string candidate_summary(const MeasuredResult& result);

/// The terminal's summary: the forward split's table as text, and the joints that meet the
/// target.
std::string measured_headline(const MeasuredResult& result, double target);

/// The measured arm at a glance (for the first screen): per joint the RMSE against the torque
/// sensor on the held-out files of the maker's estimate and of tpf's models (identified; friction
/// fitted against the sensor with the current low-pass), and on which joints the goal is met.
void add_measured_headline(HtmlReport& page, const MeasuredResult& result, double target,
                           int width);

/// The terminal's short summary (a dozen lines): per joint the maker's estimate and tpf's models
/// of the first screen (add_measured_headline) against the sensor, and where the goal is met.
std::string measured_brief(const MeasuredResult& result, double target);

/// The MEASURED section of the demo's index page.
void add_measured_summary(HtmlReport& page, const MeasuredResult& result, double target);

/// Writes measured.html and measured.json into `folder`.
void write_measured_report(const MeasuredResult& result, const MeasuredOptions& options,
                           const std::filesystem::path& folder);

/// The numbers as JSON text.
std::string measured_json(const MeasuredResult& result, double target);

}  // namespace tpf::offline
