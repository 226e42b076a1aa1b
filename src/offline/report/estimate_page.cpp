#include "offline/report/estimate_page.hpp"

#include <cmath>
#include <cstdio>
#include <limits>

#include "core/common/unoptimised_when_sanitized.hpp"
#include "offline/log/log.hpp"
#include "offline/report/line_plot.hpp"

TPF_UNOPTIMISED_WHEN_SANITIZED_BEGIN

namespace tpf::offline {

namespace {

std::string episode_cell(double v, const char* format) {
  char text[48];
  std::snprintf(text, sizeof text, format, v);
  return text;
}

/// A bar at height `level` over the rows where `flags` is nonzero (NaN elsewhere: no line).
Series contact_bar(const std::string& name, const Eigen::VectorXd& t, const Eigen::VectorXd& flags,
                   double level, const std::string& colour) {
  Series s{name, t, Eigen::VectorXd::Constant(t.size(), std::numeric_limits<double>::quiet_NaN()),
           colour};
  for (Eigen::Index r = 0; r < t.size(); ++r)
    if (std::isfinite(flags[r]) && flags[r] != 0.0) s.y[r] = level;
  return s;
}

std::string episode_joint_list(const std::vector<int>& joints) {
  std::string list;
  for (int j : joints) {
    if (!list.empty()) list += ' ';
    list += std::to_string(j + 1);
  }
  return list.empty() ? "-" : list;
}

}  // namespace

Table episode_table(const std::vector<ContactEpisode>& episodes, int joints) {
  Table table;
  table.header = {"#", "start [s]", "end [s]", "duration [s]", "joints"};
  for (int j = 1; j <= joints; ++j)
    table.header.push_back("peak |tau" + std::to_string(j) + "| [N*m]");
  for (std::size_t k = 0; k < episodes.size(); ++k) {
    const ContactEpisode& e = episodes[k];
    std::vector<std::string> row{
        std::to_string(k + 1), episode_cell(e.start_s, "%.3f"), episode_cell(e.end_s, "%.3f"),
        episode_cell(e.end_s - e.start_s, "%.3f"), episode_joint_list(e.joints)};
    for (int j = 0; j < joints; ++j)
      row.push_back(episode_cell(e.peak_abs_torque[j], "%.3g"));
    table.rows.push_back(std::move(row));
  }
  return table;
}

HtmlReport estimate_page(const EstimatePageData& d) {
  HtmlReport page("tpf estimate: " + d.log);
  page.wide();
  if (d.simulated)
    page.mark_simulated("a digital-twin log (" + d.provenance + ")");
  else
    page.mark_measured(d.provenance);
  page.list(d.notes);
  std::vector<Series> series;
  double top = 0.0;
  for (Eigen::Index j = 0; j < d.tau_ext.cols(); ++j) {
    series.push_back({"joint " + std::to_string(j + 1), d.t, d.tau_ext.col(j), ""});
    for (Eigen::Index r = 0; r < d.tau_ext.rows(); ++r)
      if (std::isfinite(d.tau_ext(r, j))) top = std::max(top, std::abs(d.tau_ext(r, j)));
  }
  top = top > 0.0 ? top : 1.0;
  series.push_back(contact_bar("contact (estimated)", d.t, d.contact, 1.1 * top, "#000000"));
  if (d.truth_contact.size() == d.t.size())
    series.push_back(
        contact_bar("contact (ground truth)", d.t, d.truth_contact, -1.1 * top, "#999999"));
  PlotOptions options;
  options.title = "estimated external joint torque";
  options.x_label = "t [s]";
  options.y_label = "tau_ext [N*m]";
  options.height = 360;
  page.figure(line_plot(options, series),
              "The run-time estimator's external torque per joint; the bar above the curves "
              "spans the cycles in which it believed a contact" +
                  std::string(d.truth_contact.size() == d.t.size()
                                  ? ", the bar below those of the ground truth."
                                  : "."));
  page.heading(std::to_string(d.episodes.size()) + " contact episodes");
  Table table = episode_table(d.episodes, static_cast<int>(d.tau_ext.cols()));
  table.caption =
      "joints: those whose peak |tau_ext| exceeds their static dead band; end: the first cycle "
      "out of contact";
  page.table(table);
  return page;
}

}  // namespace tpf::offline

TPF_UNOPTIMISED_WHEN_SANITIZED_END
