#include "offline/samples/held_out_rows.hpp"

#include <algorithm>
#include <cmath>

namespace tpf::offline {

std::vector<char> interleaved_heldout_blocks(const Eigen::VectorXd& t,
                                             const SampleOptions& options) {
  std::vector<char> heldout(static_cast<std::size_t>(t.size()), 0);
  for (Eigen::Index k = 0; k < t.size(); ++k) {
    const long block = static_cast<long>(std::floor((t[k] - t[0]) / options.block_s));
    heldout[static_cast<std::size_t>(k)] =
        (block % options.heldout_every) == options.heldout_every - 1;
  }
  return heldout;
}

std::vector<char> file_group_rows(const Log& log, const std::vector<std::size_t>& files) {
  std::vector<char> rows(static_cast<std::size_t>(log.rows()), 0);
  for (std::size_t f : files) {
    const auto [begin, end] = log.file_rows(f);
    std::fill(rows.begin() + begin, rows.begin() + end, 1);
  }
  return rows;
}

void decide_held_out_rows(const Log& log, const SampleOptions& options, JointSamples& s) {
  const std::size_t n = static_cast<std::size_t>(s.size());
  s.heldout.assign(n, options.all_held_out ? 1 : 0);
  s.heldout_file = 0;
  s.heldout_file_groups.clear();
  s.heldout_group = 0;
  s.repeats.clear();
  if (options.all_held_out || !options.hold_out) return;
  const auto rows = static_cast<Eigen::Index>(n);
  const bool by_file =
      log.file_starts.size() > 1 && log.file_starts.back() > 0 && log.file_starts.back() < rows;
  if (!by_file) {
    s.heldout = interleaved_heldout_blocks(s.t, options);
    return;
  }
  s.repeats = repeated_motions(log, s, options.repeat_tolerance);
  s.heldout_file_groups = repeated_motion_groups(log.file_count(), s.repeats);
  for (std::size_t g = 0; g < s.heldout_file_groups.size(); ++g)
    if (s.heldout_file_groups[g].back() + 1 == log.file_count()) s.heldout_group = g;
  if (s.heldout_file_groups.size() > 1) {
    s.heldout = file_group_rows(log, s.heldout_file_groups[s.heldout_group]);
    s.heldout_file = static_cast<int>(log.file_starts.size());
  } else {
    s.heldout = interleaved_heldout_blocks(s.t, options);
  }
}

}  // namespace tpf::offline
