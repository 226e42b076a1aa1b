#include "offline/fit/gram_row_block.hpp"

#include <algorithm>
#include <utility>
#include <vector>

#include "offline/common/eigen_order_kernels.hpp"

namespace tpf::offline {
namespace {

using Index = Eigen::Index;

/// Eigen's own on the rows gathered from their panels.
void eigen_rank_update(Eigen::MatrixXd& G, const double* panels, Index depth, Index panel_stride) {
  Eigen::MatrixXd rows(depth, G.rows());
  for (Index k = 0; k < depth; ++k)
    for (Index i = 0; i < G.rows(); ++i)
      rows(k, i) = panels[(i / 4) * panel_stride + k * 4 + i % 4];
  G.selfadjointView<Eigen::Lower>().rankUpdate(rows.transpose());
}

#if TPF_EIGEN_ORDER_AVX

using Traits = Eigen::internal::gebp_traits<double, double>;
// The kernel whose order is reproduced: 4 × 4 register blocks of 2-double packets.
constexpr bool kGramOrderKnown = Traits::mr == 4 && Traits::nr == 4 && Traits::LhsProgress == 2;

/// Eigen's blocking of the depth (kc) and of the rows (mc) for this rank update
/// (SelfadjointProduct.h, GeneralMatrixMatrixTriangular.h): they depend on the CPU's caches.
std::pair<Index, Index> eigen_blocking(Index size, Index depth) {
  Eigen::internal::gemm_blocking_space<Eigen::ColMajor, double, double, Eigen::Dynamic,
                                       Eigen::Dynamic, Eigen::Dynamic>
      blocking(size, size, depth, 1, false);
  Index mc = std::min(size, blocking.mc());
  if (mc > Traits::nr) mc = (mc / Traits::nr) * Traits::nr;
  return {blocking.kc(), mc};
}

/// In a gebp call of `rows` rows, the first of the rows its one-packet path takes and their
/// count (0 or 2): after the whole 4-row blocks, before a last single row.
std::pair<Index, Index> one_packet_rows(Index rows) {
  const Index first = (rows / 4) * 4;
  return {first, ((rows - first) / 2) * 2};
}

/// The entries Eigen sums as two halves, even and odd k (lhs_process_one_packet against a panel
/// of four columns), as (row i, first column j) of four entries (i, j … j + 3), all below the
/// diagonal: the one-packet rows of each gebp call of the triangular product, left of each row
/// block's diagonal block and below each 4 × 4 diagonal micro block.
std::vector<std::pair<Index, Index>> split_sum_quads(Index size, Index mc) {
  std::vector<std::pair<Index, Index>> quads;
  const auto add_rows = [&](Index first_row, Index rows, Index first_col, Index cols) {
    const auto [first, count] = one_packet_rows(rows);
    for (Index r = first; r < first + count; ++r)
      for (Index c = 0; c + 4 <= cols; c += 4)
        quads.emplace_back(first_row + r, first_col + c);
  };
  for (Index i2 = 0; i2 < size; i2 += mc) {
    const Index block = std::min(i2 + mc, size) - i2;
    add_rows(i2, block, 0, i2);
    for (Index j = 0; j + 4 <= block; j += 4)
      add_rows(i2 + j + 4, block - j - 4, i2 + j, 4);
  }
  return quads;
}

/// Σ r_k[i]·r_k[j … j + 3] over k in [begin, end) as Eigen's one-packet path sums it: the even
/// and the odd k of whole groups of 8 apart, added, then the rest in order; added to `sums`.
/// j is a multiple of 4 (split_sum_quads): the four columns are one panel.
__attribute__((target("avx"))) void add_split_sums(const double* panels, Index panel_stride,
                                                   Index i, Index j, Index begin, Index end,
                                                   double* sums) {
  const double* row_i = panels + (i / 4) * panel_stride + i % 4;
  const double* quad = panels + (j / 4) * panel_stride;
  const Index peeled = begin + ((end - begin) & ~Index{7});
  __m256d even = _mm256_setzero_pd(), odd = _mm256_setzero_pd();
  for (Index k = begin; k < peeled; k += 2) {
    even = _mm256_add_pd(
        even, _mm256_mul_pd(_mm256_broadcast_sd(row_i + 4 * k), _mm256_loadu_pd(quad + 4 * k)));
    odd = _mm256_add_pd(odd, _mm256_mul_pd(_mm256_broadcast_sd(row_i + 4 * k + 4),
                                           _mm256_loadu_pd(quad + 4 * k + 4)));
  }
  __m256d sum = _mm256_add_pd(even, odd);
  for (Index k = peeled; k < end; ++k)
    sum = _mm256_add_pd(
        sum, _mm256_mul_pd(_mm256_broadcast_sd(row_i + 4 * k), _mm256_loadu_pd(quad + 4 * k)));
  _mm256_storeu_pd(sums, _mm256_add_pd(_mm256_loadu_pd(sums), sum));
}

/// G.lower += Σ_{k in [begin, end)} r_k r_kᵀ, each entry's sum from zero in k order, then added:
/// tiles of 8 rows × 4 columns (two panels against one), one AVX lane per entry (multiply, then
/// add: no fused rounding).
__attribute__((target("avx"))) void add_sequential_sums(Eigen::MatrixXd& G, const double* panels,
                                                        Index panel_stride, Index begin,
                                                        Index end) {
  const Index size = G.rows();
  alignas(32) double tile[4][8];
  for (Index jb = 0; jb < size; jb += 4)
    for (Index ib = jb; ib < size; ib += 8) {
      const double* rows_low = panels + (ib / 4) * panel_stride;
      const double* rows_high = rows_low + panel_stride;
      const double* columns = panels + (jb / 4) * panel_stride;
      __m256d low[4], high[4];
      for (int c = 0; c < 4; ++c)
        low[c] = high[c] = _mm256_setzero_pd();
      for (Index k = begin; k < end; ++k) {
        const __m256d a0 = _mm256_loadu_pd(rows_low + 4 * k);
        const __m256d a1 = _mm256_loadu_pd(rows_high + 4 * k);
        for (int c = 0; c < 4; ++c) {
          const __m256d b = _mm256_broadcast_sd(columns + 4 * k + c);
          low[c] = _mm256_add_pd(low[c], _mm256_mul_pd(a0, b));
          high[c] = _mm256_add_pd(high[c], _mm256_mul_pd(a1, b));
        }
      }
      for (int c = 0; c < 4; ++c) {
        _mm256_store_pd(tile[c], low[c]);
        _mm256_store_pd(tile[c] + 4, high[c]);
      }
      for (Index c = 0; c < 4 && jb + c < size; ++c)
        for (Index r = std::max<Index>(0, jb + c - ib); r < 8 && ib + r < size; ++r)
          G(ib + r, jb + c) += tile[c][r];
    }
}

#endif  // TPF_EIGEN_ORDER_AVX

}  // namespace

GramRowBlock::GramRowBlock(Index size, Index capacity)
    : size_(size), capacity_(capacity), panel_stride_(4 * capacity) {
  panels_.assign(static_cast<std::size_t>(((size + 3) / 4 + 1) * panel_stride_), 0.0);
}

void GramRowBlock::append(const double* values) {
  for (Index c = 0; c < size_; ++c)
    at(rows_, c) = values[c];
  ++rows_;
}

void GramRowBlock::append_augmented(const double* features, double y) {
  const Index count = size_ - 2;
  double* row = &at(rows_, 0);
  Index c = 0;
  for (; c + 4 <= count; c += 4, row += panel_stride_)
    for (int lane = 0; lane < 4; ++lane)  // a loop of 4, not a call to memmove
      row[lane] = features[c + lane];
  for (; c < count; ++c)
    at(rows_, c) = features[c];
  at(rows_, count) = y;
  at(rows_, count + 1) = 1.0;
  ++rows_;
}

void GramRowBlock::add_to_lower(Eigen::MatrixXd& G) {
  const Index depth = rows_;
  rows_ = 0;
  if (depth == 0) return;
  const double* panels = panels_.data();
#if TPF_EIGEN_ORDER_AVX
  if (kGramOrderKnown && cpu_runs_eigen_order_kernels()) {
    const auto [kc, mc] = eigen_blocking(size_, depth);
    const std::vector<std::pair<Index, Index>> quads = split_sum_quads(size_, mc);
    std::vector<double> split(4 * quads.size());
    for (Index k2 = 0; k2 < depth; k2 += kc) {
      const Index end = std::min(k2 + kc, depth);
      // The split sums first (the tiles overwrite their entries), G's value added in order.
      for (std::size_t q = 0; q < quads.size(); ++q) {
        const auto [i, j] = quads[q];
        for (int c = 0; c < 4; ++c)
          split[4 * q + c] = G(i, j + c);
        add_split_sums(panels, panel_stride_, i, j, k2, end, &split[4 * q]);
      }
      add_sequential_sums(G, panels, panel_stride_, k2, end);
      for (std::size_t q = 0; q < quads.size(); ++q)
        for (int c = 0; c < 4; ++c)
          G(quads[q].first, quads[q].second + c) = split[4 * q + c];
    }
    return;
  }
#endif
  eigen_rank_update(G, panels, depth, panel_stride_);
}

}  // namespace tpf::offline
