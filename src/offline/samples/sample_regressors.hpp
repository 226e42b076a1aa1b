// The rigid-body regressor of every sample, computed once per log: identification and diagnosis
// pass over the samples several times (a first fit, the candidates' Gram matrices, predictions),
// and Y(q, q̇, q̈) depends only on the motion, so every pass reads it instead of recomputing it.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "offline/common/run_time_types.hpp"
#include "offline/samples/joint_samples.hpp"

namespace tpf::offline {

/// The entries of Y in `columns` (those a design's families read: EffectDesign's
/// regressor_columns) of every valid sample, as compute_regressor gives them (the same doubles).
/// Only entries that can be non-zero are stored: row j of link k's columns is zero for k < j (a
/// link moves no joint after it), an armature column only acts on its own joint.
class SampleRegressors {
 public:
  /// One compute_regressor per valid sample (two threads).
  SampleRegressors(const ModelX& model, std::vector<int> columns, const JointSamples& samples);

  Eigen::Index size() const { return values_.cols(); }
  /// Whether column `column` of Y is stored (its entries that can be non-zero).
  bool holds(int column) const;
  /// Writes the stored entries of sample k into Y (N × 13N); the others are left as they are
  /// (zero in a Y that was zeroed once). Precondition: sample k is valid.
  void load(Eigen::Index k, Eigen::MatrixXd& Y) const;

 private:
  struct Entry {
    int row, column;
  };
  std::vector<int> columns_;    ///< stored columns, ascending
  std::vector<Entry> entries_;  ///< stored entries, in storage order
  Eigen::MatrixXd values_;      ///< entries × samples: one sample's entries contiguous
};

}  // namespace tpf::offline
