#include "offline/pipeline/tiago_report.hpp"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "core/common/atomic_file.hpp"
#include "core/common/unoptimised_when_sanitized.hpp"
#include "offline/report/text_format.hpp"

TPF_UNOPTIMISED_WHEN_SANITIZED_BEGIN

namespace tpf::offline {
namespace {

/// "1 torso_lift_joint".
std::string tiago_joint_label(const TiagoResult& r, int j) {
  return std::to_string(j + 1) + " " + r.joint_names[static_cast<std::size_t>(j)];
}

bool is_dead(const TiagoResult& r, int j) {
  return std::find(r.dead_joints.begin(), r.dead_joints.end(), j + 1) != r.dead_joints.end();
}

std::string si_unit(const TiagoResult& r, int j) {
  return r.prismatic[static_cast<std::size_t>(j)] ? "N" : "N·m";
}

std::string goal_text(const TiagoGoal& g) {
  return g.target < 0 ? format_sentence("−%.0f %%", -g.target) : "≤ nominal";
}

/// The joints (1-based, as text) whose goal in `regime` is met or missed.
std::vector<std::string> joints_where(const TiagoResult& r, Regime regime, bool met) {
  std::vector<std::string> out;
  for (const TiagoGoal& g : r.goals)
    if (g.regime == regime && g.met == met) out.push_back(std::to_string(g.joint + 1));
  return out;
}

std::string list_or_none(const std::vector<std::string>& items) {
  return items.empty() ? std::string("none") : joined(items, ", ");
}

/// One missed cell in numbers, with the onsets the data hold for it.
std::string missed_cell(const TiagoResult& r, const TiagoGoal& g) {
  const TiagoEvents& e = r.events[static_cast<std::size_t>(g.joint)];
  return "joint " + std::to_string(g.joint + 1) + " " + std::string(regime_name(g.regime)) + ": " +
         format_number(g.nominal) + " → " + format_number(g.compensated) + " mA (" +
         format_percent_change(g.nominal, g.compensated) + ", goal " + goal_text(g) + "; " +
         std::to_string(g.rows) + " held-out rows, " + std::to_string(e.held_out.starts) +
         " starts there, " + std::to_string(e.trained.starts) + " starts and " +
         std::to_string(e.trained.reversals) + " reversals trained on)";
}

nlohmann::json stats_json(const ResidualStats& s) {
  return {{"count", s.count}, {"rmse", s.rmse}, {"std", s.std}, {"mean", s.mean}};
}

nlohmann::json rows_json(const std::vector<ResidualRow>& rows) {
  nlohmann::json out = nlohmann::json::array();
  for (const ResidualRow& row : rows)
    out.push_back({{"joint", row.joint + 1},
                   {"regime", regime_name(row.regime)},
                   {"nominal_ma", stats_json(row.nominal)},
                   {"compensated_ma", stats_json(row.compensated)}});
  return out;
}

void add_details(HtmlReport& page, const TiagoResult& r, const TiagoOptions& o) {
  page.open_details("Starts from rest and reversals per joint, in each part");
  page.table(tiago_events_table(r));
  page.close_details();
  page.open_details("The run time with the trainer's gate");
  page.paragraph(
      "The trainer scores each network on the fitted part's last " +
      format_number(100 * o.gate_share, 3) + " % (t ≥ " + format_number(r.t_gate, 4) +
      " s) and the run time keeps it only where it is not worse there in any regime scored. "
      "Those rows never rest, so the gate judges the moving regime. Networks kept: joints " +
      list_or_none([&] {
        std::vector<std::string> k;
        for (int j : r.compensated_joints)
          k.push_back(std::to_string(j));
        return k;
      }()) +
      ".");
  page.list(r.gate);
  page.close_details();
  page.open_details("Diagnose's findings on the fitted part");
  page.list(r.diagnosis_findings);
  page.close_details();
  page.open_details("The log against the robot file (identify's checks)");
  std::vector<std::string> lines = r.log_problems;
  lines.insert(lines.end(), r.log_notes.begin(), r.log_notes.end());
  page.list(lines);
  page.close_details();
  page.open_details("Source, licence and units");
  page.paragraph(std::string(kTiagoLabel) + ".");
  page.paragraph(
      "The efforts are motor currents; no torque sensor, so the reference is the current itself. "
      "K_t is the robot file's output-side constant, the motor's K_t times the gear ratio: "
      "N·m = A · K_t. The torso is prismatic: its residual is a force, N, through 203 N/A, a "
      "constant read off its resting current (SOURCE.md).");
  page.close_details();
}

/// "a–b" (or "a") of the values.
std::string range_text(std::vector<int> v) {
  if (v.empty()) return "–";
  const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
  return *lo == *hi ? std::to_string(*lo) : std::to_string(*lo) + "–" + std::to_string(*hi);
}

}  // namespace

std::string other_arm_sentence(const TiagoResult& r) {
  if (r.other_arm.empty()) return "";
  std::vector<int> single_starts, starts, reversals;
  int single = 0;
  for (const FileOnsets& f : r.other_arm) {
    if (f.single_joint >= 0) {
      ++single;
      single_starts.push_back(f.joints[static_cast<std::size_t>(f.single_joint)].starts);
      continue;
    }
    for (const MotionEvents& e : f.joints)
      starts.push_back(e.starts), reversals.push_back(e.reversals);
  }
  return "The Kinova Gen3's files hold " + range_text(single_starts) +
         " starts from rest in each of its " + std::to_string(single) +
         " single-joint files, and " + range_text(starts) + " starts and " + range_text(reversals) +
         " reversals per joint in each of the " +
         std::to_string(r.other_arm.size() - static_cast<std::size_t>(single)) +
         " others: too few to score the static-to-kinetic regime there; Table I is scored on the "
         "TIAGo.";
}

Table tiago_table_one(const TiagoResult& r) {
  Table t;
  t.header = {"joint",  "regime", "held-out rows",      "nominal [mA]", "compensated [mA]",
              "change", "goal",   "noise at rest [mA]", "verdict"};
  t.percent_column = 5;
  for (const TiagoGoal& g : r.goals)
    t.rows.push_back({tiago_joint_label(r, g.joint), std::string(regime_name(g.regime)),
                      std::to_string(g.rows), format_number(g.nominal),
                      format_number(g.compensated), format_percent_change(g.nominal, g.compensated),
                      goal_text(g), format_number(r.noise_ma[g.joint], 3),
                      g.met ? "met" : "missed"});
  t.caption =
      "Table I, MEASURED (TIAGo, Apache-2.0): current residual RMSE on the held-out part, "
      "nominal model against nominal − network output.";
  return t;
}

Table tiago_residual_table(const TiagoResult& r) {
  Table t;
  t.header = {"joint",        "K_t·ratio",        "identified [A]",
              "nominal [A]",  "compensated [A]",  "with the gate [A]",
              "nominal [SI]", "compensated [SI]", "change",
              "note"};
  t.percent_column = 8;
  for (int j = 0; j < static_cast<int>(r.residual.size()); ++j) {
    const TiagoJointResidual& x = r.residual[static_cast<std::size_t>(j)];
    const std::string unit = si_unit(r, j);
    t.rows.push_back({tiago_joint_label(r, j),
                      format_number(r.torque_constant[j], 3) + (r.prismatic[j] ? " N/A" : " N·m/A"),
                      format_number(x.identified_ma / 1000.0), format_number(x.nominal_ma / 1000.0),
                      format_number(x.compensated_ma / 1000.0), format_number(x.gated_ma / 1000.0),
                      format_number(x.nominal_si) + " " + unit,
                      format_number(x.compensated_si) + " " + unit,
                      format_percent_change(x.nominal_si, x.compensated_si),
                      is_dead(r, j) ? "dead current channel: not a claim" : ""});
  }
  t.caption = "Held-out current residual over every regime, per joint (MEASURED, TIAGo).";
  return t;
}

Table tiago_events_table(const TiagoResult& r) {
  Table t;
  t.header = {"joint",
              "starts, fitted",
              "reversals, fitted",
              "starts, trained on",
              "starts, held out",
              "reversals, held out"};
  for (int j = 0; j < static_cast<int>(r.events.size()); ++j) {
    const TiagoEvents& e = r.events[static_cast<std::size_t>(j)];
    t.rows.push_back({tiago_joint_label(r, j), std::to_string(e.fit.starts),
                      std::to_string(e.fit.reversals), std::to_string(e.trained.starts),
                      std::to_string(e.held_out.starts), std::to_string(e.held_out.reversals)});
  }
  t.caption =
      "A start: |q̇| reaching the static threshold after rest (a static-to-kinetic "
      "window); a reversal: q̇ changing sign beyond 0.01 rad/s (m/s at the torso).";
  return t;
}

std::string tiago_goal_sentence(const TiagoResult& r, const TiagoOptions& o) {
  std::string text = std::string(r.all_goals_met() ? "Goal met" : "Goal missed") + " (static " +
                     format_sentence("−%.0f %%", 100 * o.static_target) + ", static-to-kinetic " +
                     format_sentence("−%.0f %%", 100 * o.transition_target) +
                     ", no regime above the nominal model). Static met on joints " +
                     list_or_none(joints_where(r, Regime::Static, true)) +
                     "; static-to-kinetic on " +
                     list_or_none(joints_where(r, Regime::StaticToKinetic, true)) +
                     "; moving at or below nominal on " +
                     list_or_none(joints_where(r, Regime::Moving, true)) + ".";
  return text;
}

std::string tiago_split_sentence(const TiagoResult& r) {
  return "Held out by time: fitted on t < " + format_number(r.t_split, 4) + " s (" +
         std::to_string(r.rows_fit) + " rows), scored on t ≥ " + format_number(r.t_split, 4) +
         " … " + format_number(r.t_end, 4) + " s (" + std::to_string(r.rows_held_out) +
         " rows). The networks train on t < " + format_number(r.t_gate, 4) + " s.";
}

void add_tiago_headline(HtmlReport& page, const TiagoResult& r, const TiagoOptions& o) {
  page.heading("TIAGo (MEASURED): Table I held out by time");
  Table t;
  t.header = {"joint", "static [mA]", "change", "static-to-kinetic [mA]", "change"};
  t.percent_column = 2;
  for (const int j : o.table_joints) {
    const ResidualRow& s = r.row(j, Regime::Static);
    const ResidualRow& k = r.row(j, Regime::StaticToKinetic);
    t.rows.push_back({tiago_joint_label(r, j),
                      format_number(s.nominal.rmse) + " → " + format_number(s.compensated.rmse),
                      format_percent_change(s.nominal.rmse, s.compensated.rmse),
                      format_number(k.nominal.rmse) + " → " + format_number(k.compensated.rmse),
                      format_percent_change(k.nominal.rmse, k.compensated.rmse)});
  }
  page.table(t);
  page.paragraph(tiago_goal_sentence(r, o) + " Data: TIAGo log, T. Nguyen, Apache-2.0.");
  page.paragraph(other_arm_sentence(r));
  page.nav({{"tiago.html", "The TIAGo in full", ""}});
}

void write_tiago_report(const TiagoResult& r, const TiagoOptions& o,
                        const std::filesystem::path& out) {
  HtmlReport page("TIAGo: Table I on a measured arm, held out by time");
  page.mark_measured("PAL Robotics TIAGo log, T. Nguyen (FIGAROH), Apache-2.0");
  page.table(tiago_table_one(r));
  page.paragraph(tiago_split_sentence(r) + " " + tiago_goal_sentence(r, o));
  std::vector<std::string> missed;
  for (const TiagoGoal& g : r.goals)
    if (!g.met) missed.push_back(missed_cell(r, g));
  if (!missed.empty()) {
    page.open_details("Where the goal is missed, in numbers");
    page.list(missed);
    page.close_details();
  }
  page.paragraph(other_arm_sentence(r));
  page.table(tiago_residual_table(r));
  page.paragraph("Identify, then diagnose, on the fitted part; one network per joint; " +
                 format_number(r.seconds, 3) + " s. Arm 5–7 log all-but-dead currents.");
  add_details(page, r, o);
  page.nav({{"index.html", "index", ""}, {"tiago.json", "tiago.json", ""}});
  page.write(out / "tiago.html");
  AtomicFile json(out / "tiago.json");
  json.write(tiago_json(r, o));
  json.commit();
}

std::string tiago_json(const TiagoResult& r, const TiagoOptions& o) {
  using nlohmann::json;
  json j;
  j["data"] = kTiagoLabel;
  j["split"] = {{"t_begin", r.t_begin},
                {"t_split", r.t_split},
                {"t_end", r.t_end},
                {"rows_fit", r.rows_fit},
                {"rows_held_out", r.rows_held_out},
                {"t_gate", r.t_gate},
                {"rows_trained", r.rows_trained},
                {"rows_gate", r.rows_gate},
                {"fit_share", o.fit_share}};
  json joints = json::array();
  for (int k = 0; k < static_cast<int>(r.residual.size()); ++k) {
    const TiagoJointResidual& x = r.residual[static_cast<std::size_t>(k)];
    const TiagoEvents& e = r.events[static_cast<std::size_t>(k)];
    joints.push_back({{"name", r.joint_names[static_cast<std::size_t>(k)]},
                      {"prismatic", static_cast<bool>(r.prismatic[static_cast<std::size_t>(k)])},
                      {"torque_constant", r.torque_constant[k]},
                      {"gear_ratio", r.gear_ratio[k]},
                      {"dead", is_dead(r, k)},
                      {"residual_ma",
                       {{"identified", x.identified_ma},
                        {"nominal", x.nominal_ma},
                        {"compensated", x.compensated_ma},
                        {"with_gate", x.gated_ma}}},
                      {"residual_si",
                       {{"identified", x.identified_si},
                        {"nominal", x.nominal_si},
                        {"compensated", x.compensated_si},
                        {"with_gate", x.gated_si}}},
                      {"events",
                       {{"fit_starts", e.fit.starts},
                        {"fit_reversals", e.fit.reversals},
                        {"trained_starts", e.trained.starts},
                        {"held_out_starts", e.held_out.starts},
                        {"held_out_reversals", e.held_out.reversals}}}});
  }
  j["joints"] = joints;
  j["table_one"] = rows_json(r.table);
  j["table_one_with_gate"] = rows_json(r.gated_table);
  j["goal_met"] = r.all_goals_met();
  j["compensated_joints"] = r.compensated_joints;
  return j.dump(2);
}

}  // namespace tpf::offline

TPF_UNOPTIMISED_WHEN_SANITIZED_END
