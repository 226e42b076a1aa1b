// The prediction kernel of identify and diagnose against Eigen's row-vector × matrix product:
// the same bits for every feature count and number of parameter sets, zeros and magnitudes
// that round differently in another order included.
#include "offline/fit/theta_products.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

namespace tpf::test {
namespace {

TEST(ThetaProducts, EqualEigensProductBitForBit) {
  std::mt19937_64 rng(23);
  std::normal_distribution<double> normal(0.0, 1.0);
  const auto value = [&] { return normal(rng) * std::exp(3.0 * normal(rng)); };
  int differing = 0, compared = 0;
  for (Eigen::Index features = 1; features <= 90; features += features < 12 ? 1 : 7)
    for (Eigen::Index sets = 1; sets <= 11; ++sets) {
      Eigen::MatrixXd thetas(features, sets);
      for (Eigen::Index a = 0; a < features; ++a)
        for (Eigen::Index i = 0; i < sets; ++i)
          thetas(a, i) = rng() % 3 == 0 ? 0.0 : value();  // groups without a coefficient
      const offline::ThetaProducts products(thetas);
      for (int sample = 0; sample < 8; ++sample) {
        Eigen::RowVectorXd phi(features);
        for (Eigen::Index a = 0; a < features; ++a)
          phi[a] = value();
        Eigen::RowVectorXd expected(sets);
        expected.noalias() = phi * thetas;
        std::vector<double> got(static_cast<std::size_t>(sets));
        products.apply(phi.data(), got.data());
        for (Eigen::Index i = 0; i < sets; ++i, ++compared)
          differing +=
              std::memcmp(&expected[i], &got[static_cast<std::size_t>(i)], sizeof(double)) != 0;
      }
    }
  EXPECT_EQ(differing, 0) << "of " << compared;
  EXPECT_GT(compared, 10000);
}

}  // namespace
}  // namespace tpf::test
