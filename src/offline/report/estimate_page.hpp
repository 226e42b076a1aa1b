// The page `tpf estimate` writes beside its log: τ̂_ext against time with the contacts marked, and
// the table of the contact episodes the estimator found.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "offline/replay/contact_episodes.hpp"
#include "offline/report/html_report.hpp"
#include "offline/report/text_table.hpp"

namespace tpf::offline {

/// What the page shows of one replayed log.
struct EstimatePageData {
  std::string log;          ///< the input log's path
  bool simulated = false;   ///< a twin log (SIMULATED banner), else MEASURED
  std::string provenance;   ///< the log's source and licence, for the banner
  Eigen::VectorXd t;        ///< [s]
  Eigen::MatrixXd tau_ext;  ///< T × N, est_tau_ext [N·m]
  Eigen::VectorXd contact;  ///< est_contact (1/0, NaN skipped)
  /// gt_contact of a twin log (nonzero: a pad in contact), empty when the log has none.
  Eigen::VectorXd truth_contact;
  std::vector<ContactEpisode> episodes;
  std::vector<std::string> notes;  ///< model, parameter and weight files
};

/// The episodes as a table: #, start [s], end [s], duration [s], joints (1-based), and the
/// peak |τ̂_ext| of each joint [N·m].
Table episode_table(const std::vector<ContactEpisode>& episodes, int joints);

/// The page: banner, notes, the plot (one line per joint; contacts marked as bars above the
/// curves, the ground truth's below them when the log has it) and the episode table.
HtmlReport estimate_page(const EstimatePageData& data);

}  // namespace tpf::offline
