// Files of a several-file log that repeat one motion (a fit on one would be scored on its own
// motion, so they are held out together), and the range of q a set of rows covers.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <utility>
#include <vector>

#include "offline/log/log.hpp"

namespace tpf::offline {

struct JointSamples;

/// Two files with the same motion, and how far their current-based torques differ.
struct RepeatedMotion {
  std::size_t first = 0, second = 0;          ///< indices of the log's files
  Eigen::Index common_samples = 0;            ///< the shorter file's rows, compared row by row
  double rms_position_difference = 0.0;       ///< rad, the largest per-joint RMS of Δq
  double max_position_difference = 0.0;       ///< rad, over all joints
  std::vector<double> torque_rms_difference;  ///< per joint, RMS of Δ(K_t·i) [N·m]
};

/// The pairs of files of `log` (first < second, indices of the log's files) that repeat one
/// motion: over their common length (the shorter file's rows from each file's start, valid rows
/// of both), the RMS of Δq is below `tolerance` [rad] on every joint.
std::vector<RepeatedMotion> repeated_motions(const Log& log, const JointSamples& s,
                                             double tolerance);

/// The files 0 … files−1 in groups that repeat one motion (joined through `repeats`), each
/// group's files in order, the groups ordered by their first file.
std::vector<std::vector<std::size_t>> repeated_motion_groups(
    std::size_t files, const std::vector<RepeatedMotion>& repeats);

/// Per joint: [min, max] of q over the valid samples of `s` where `rows` is non-zero (every
/// valid sample when `rows` is empty); [+inf, −inf] when there is none.
std::vector<std::pair<double, double>> position_range(const JointSamples& s,
                                                      const std::vector<char>& rows = {});

}  // namespace tpf::offline
