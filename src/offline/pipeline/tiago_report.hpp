// The TIAGo study's report (MEASURED): tiago.html led by Table I held out by time, tiago.json
// with the same numbers, and the headline panel of the demo's index.
#pragma once

#include <filesystem>
#include <string>

#include "offline/pipeline/tiago_study.hpp"
#include "offline/report/html_report.hpp"

namespace tpf::offline {

/// Table I per joint and regime: held-out rows, nominal and compensated RMSE [mA], change, the
/// goal and whether it is met.
Table tiago_table_one(const TiagoResult& r);

/// Per joint: the held-out current residual over every regime in A and in N·m (N at the torso)
/// through the output-side K_t (the motor's K_t times the gear ratio), per model.
Table tiago_residual_table(const TiagoResult& r);

/// Per joint: starts from rest and reversals in the fitted part (and the rows trained on) and in
/// the held-out part.
Table tiago_events_table(const TiagoResult& r);

/// "Goal … met on … / missed on …" and, per missed cell, its numbers and the data behind it.
std::string tiago_goal_sentence(const TiagoResult& r, const TiagoOptions& o);

/// The other arm's onsets (TiagoResult::other_arm) in a sentence: starts per single-joint file
/// and reversals per joint in the others, ranges; empty when none were counted.
std::string other_arm_sentence(const TiagoResult& r);

/// The split in a sentence: times, rows, the gate's rows.
std::string tiago_split_sentence(const TiagoResult& r);

/// The index's panel: Table I at a glance (static and static-to-kinetic per joint) and the goal.
void add_tiago_headline(HtmlReport& page, const TiagoResult& r, const TiagoOptions& o);

/// Writes out/tiago.html and out/tiago.json.
void write_tiago_report(const TiagoResult& r, const TiagoOptions& o,
                        const std::filesystem::path& out);

/// The numbers of tiago.json as text.
std::string tiago_json(const TiagoResult& r, const TiagoOptions& o);

}  // namespace tpf::offline
