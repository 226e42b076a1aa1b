// Which rows of a log are held out: the one decision identify, diagnose, the measured study and
// tpf validate all read (JointSamples::heldout and the file groups beside it), so that one log
// scores every tool on the same rows.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "offline/log/log.hpp"
#include "offline/samples/joint_samples.hpp"

namespace tpf::offline {

/// Sets the held-out split of `samples` (extracted from `log`; its valid rows and q decide which
/// files repeat one motion):
/// - options.all_held_out: every row (a log scored with a model fitted on other logs);
/// - !options.hold_out: none (the caller scores on other logs);
/// - a several-file log (Log::file_starts): its files grouped where they repeat one motion
///   (repeated_motions with options.repeat_tolerance), and the group of the last file held out
///   (heldout_file = the file count); when every file repeats one motion (one group), no file is
///   independent of another and the log is split in blocks as one file is (heldout_file = 0);
/// - a one-file log: interleaved blocks (interleaved_heldout_blocks).
void decide_held_out_rows(const Log& log, const SampleOptions& options, JointSamples& samples);

/// The interleaved held-out blocks of times `t`: block_s long from t[0], every heldout_every-th
/// held out (1), the others 0.
std::vector<char> interleaved_heldout_blocks(const Eigen::VectorXd& t,
                                             const SampleOptions& options);

/// The rows of `files` (indices of `log`'s files) marked 1, the others 0: the rows of a group of
/// JointSamples::heldout_file_groups, held out one at a time by diagnose's transfer test.
std::vector<char> file_group_rows(const Log& log, const std::vector<std::size_t>& files);

}  // namespace tpf::offline
