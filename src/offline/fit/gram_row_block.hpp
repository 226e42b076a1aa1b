// The Gram matrix of a block of rows, Σ_k r_k r_kᵀ, added to the lower triangle of G bit for bit
// as Eigen's G.selfadjointView<Eigen::Lower>().rankUpdate(R.transpose()) adds it, in AVX
// registers where the CPU has them: the Gram accumulation of identify and diagnose.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace tpf::offline {

/// Up to `capacity` rows of `size` values, stored as the Gram kernel reads them: panels of four
/// columns, each holding its four values of every row contiguously, and a zero panel past the
/// last (a tile of 8 columns may start in the last panel).
class GramRowBlock {
 public:
  GramRowBlock(Eigen::Index size, Eigen::Index capacity);

  Eigen::Index rows() const { return rows_; }
  bool full() const { return rows_ == capacity_; }
  /// Appends the row values[0 … size).
  void append(const double* values);
  /// Appends the augmented design row [φ, y, 1], φ = features[0 … size − 2).
  void append_augmented(const double* features, double y);
  /// G.lower += Σ r rᵀ over the rows appended since the last call (G is size × size), then
  /// empties the block. Every entry is summed in the order Eigen's SSE2 product kernel sums it
  /// (its blocking of the depth, each entry's partial sum started from zero, and the entries its
  /// one-packet rows sum as even and odd halves), without fused multiply-adds: the result equals
  /// Eigen's rankUpdate to the last bit (tests/identify/gram_row_block_test.cpp). Where Eigen
  /// itself is compiled with AVX or FMA (TPF_NATIVE) or the CPU lacks AVX, Eigen's rankUpdate
  /// runs.
  void add_to_lower(Eigen::MatrixXd& G);

 private:
  double& at(Eigen::Index row, Eigen::Index column) {
    return panels_[static_cast<std::size_t>((column / 4) * panel_stride_ + row * 4 + column % 4)];
  }
  Eigen::Index size_, capacity_, panel_stride_, rows_ = 0;
  std::vector<double> panels_;
};

}  // namespace tpf::offline
