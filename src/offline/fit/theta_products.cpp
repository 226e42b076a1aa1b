#include "offline/fit/theta_products.hpp"

#include <algorithm>

#include "offline/common/eigen_order_kernels.hpp"

namespace tpf::offline {
namespace {

using Index = Eigen::Index;

/// Eigen's own product.
void eigen_products(const Eigen::MatrixXd& thetas, const double* phi, double* out) {
  const Eigen::Map<const Eigen::RowVectorXd> row(phi, thetas.rows());
  Eigen::Map<Eigen::RowVectorXd> values(out, thetas.cols());
  values.noalias() = row * thetas;
}

#if TPF_EIGEN_ORDER_AVX

// The kernel whose order is reproduced: 2-double packets, products then sums.
constexpr bool kProductOrderKnown = Eigen::internal::packet_traits<double>::size == 2 &&
                                    !Eigen::internal::packet_traits<double>::HasHalfPacket;

/// Four parameter sets per register: the even features' sum, the odd ones', their sum, the last
/// feature of an odd count, then added to the zero Eigen's destination starts from.
__attribute__((target("avx"))) void avx_products(const double* by_feature, Index features,
                                                 Index padded_sets, Index sets, const double* phi,
                                                 double* out) {
  const Index pairs_end = features & ~Index{1};
  for (Index i = 0; i < padded_sets; i += 4) {
    __m256d even = _mm256_setzero_pd(), odd = _mm256_setzero_pd();
    const double* theta = by_feature + i;
    for (Index a = 0; a < pairs_end; a += 2) {
      even = _mm256_add_pd(even, _mm256_mul_pd(_mm256_loadu_pd(theta + a * padded_sets),
                                               _mm256_broadcast_sd(phi + a)));
      odd = _mm256_add_pd(odd, _mm256_mul_pd(_mm256_loadu_pd(theta + (a + 1) * padded_sets),
                                             _mm256_broadcast_sd(phi + a + 1)));
    }
    __m256d sum = _mm256_add_pd(even, odd);
    if (pairs_end < features)
      sum = _mm256_add_pd(sum, _mm256_mul_pd(_mm256_loadu_pd(theta + pairs_end * padded_sets),
                                             _mm256_broadcast_sd(phi + pairs_end)));
    alignas(32) double values[4];
    _mm256_store_pd(values, _mm256_add_pd(_mm256_setzero_pd(), sum));
    std::copy_n(values, std::min<Index>(4, sets - i), out + i);
  }
}

#endif  // TPF_EIGEN_ORDER_AVX

}  // namespace

ThetaProducts::ThetaProducts(const Eigen::MatrixXd& thetas)
    : thetas_(thetas), padded_sets_((thetas.cols() + 3) / 4 * 4) {
  by_feature_.assign(static_cast<std::size_t>(thetas.rows() * padded_sets_), 0.0);
  for (Index a = 0; a < thetas.rows(); ++a)
    for (Index i = 0; i < thetas.cols(); ++i)
      by_feature_[static_cast<std::size_t>(a * padded_sets_ + i)] = thetas(a, i);
}

void ThetaProducts::apply(const double* phi, double* out) const {
#if TPF_EIGEN_ORDER_AVX
  // One θ: Eigen takes the product as a dot product, summed in another order; its own runs.
  if (kProductOrderKnown && thetas_.cols() > 1 && cpu_runs_eigen_order_kernels()) {
    avx_products(by_feature_.data(), thetas_.rows(), padded_sets_, thetas_.cols(), phi, out);
    return;
  }
#endif
  eigen_products(thetas_, phi, out);
}

}  // namespace tpf::offline
