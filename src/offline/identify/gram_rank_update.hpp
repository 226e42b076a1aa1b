// The Gram matrix of a block of rows, Σ_k r_k r_kᵀ, added to the lower triangle of G bit for bit
// as Eigen's G.selfadjointView<Eigen::Lower>().rankUpdate(R.transpose()) adds it, in AVX
// registers where the CPU has them: the Gram accumulation of identify and diagnose.
#pragma once

#include <Eigen/Core>

namespace tpf::offline {

/// Width of a row buffer for add_lower_gram: `size` and the padding its tiles of 8 read past
/// the end (their products are discarded).
Eigen::Index gram_row_stride(Eigen::Index size);

/// G.lower += Σ_{k < depth} r_k r_kᵀ, r_k = rows[k·stride … k·stride + G.rows()), stride ≥
/// gram_row_stride(G.rows()). Every entry is summed in the order Eigen's SSE2 product kernel sums
/// it (its blocking of the depth, each entry's partial sum started from zero, and the entries its
/// one-packet rows sum as even and odd halves), without fused multiply-adds: the result equals
/// Eigen's rankUpdate to the last bit (tests/identify/gram_rank_update_test.cpp). Where Eigen
/// itself is compiled with AVX or FMA (TPF_NATIVE) or the CPU lacks AVX, Eigen's rankUpdate runs.
void add_lower_gram(Eigen::MatrixXd& G, const double* rows, Eigen::Index depth,
                    Eigen::Index stride);

}  // namespace tpf::offline
