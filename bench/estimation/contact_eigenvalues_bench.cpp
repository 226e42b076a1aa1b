// The contact force's 3×3 eigenvalues (the Gram matrix J_c·J_cᵀ of a 3×4 contact Jacobian):
// cyclic Jacobi (symmetric_eigenvalues3, what estimate_contact_force uses) against Eigen's QR
// iteration (what it replaced), on 256 random Jacobians, a third of them ill-conditioned.
#include <benchmark/benchmark.h>

#include <Eigen/Eigenvalues>
#include <random>
#include <vector>

#include "tpf/common/symmetric_eigenvalues3.hpp"

namespace {

const std::vector<tpf::Matrix3<double>>& gram_matrices() {
  static const std::vector<tpf::Matrix3<double>> out = [] {
    std::mt19937 rng(3);
    std::normal_distribution<double> normal;
    std::vector<tpf::Matrix3<double>> m;
    for (int k = 0; k < 256; ++k) {
      Eigen::Matrix<double, 3, 4> j;
      for (int i = 0; i < 12; ++i)
        j.data()[i] = normal(rng);
      if (k % 3 == 0) j.row(2) = j.row(0) + 1e-5 * j.row(2);  // nearly rank 2
      m.push_back(j * j.transpose());
    }
    return m;
  }();
  return out;
}

void BM_ContactEigenvalues_Jacobi(benchmark::State& state) {
  const auto& m = gram_matrices();
  std::size_t i = 0;
  for (auto _ : state) {
    const tpf::Vector3<double> lambda = tpf::symmetric_eigenvalues3(m[i++ & 255]);
    benchmark::DoNotOptimize(lambda);
  }
}
BENCHMARK(BM_ContactEigenvalues_Jacobi);

void BM_ContactEigenvalues_EigenQr(benchmark::State& state) {
  const auto& m = gram_matrices();
  std::size_t i = 0;
  for (auto _ : state) {
    const Eigen::SelfAdjointEigenSolver<tpf::Matrix3<double>> eig(m[i++ & 255],
                                                                  Eigen::EigenvaluesOnly);
    benchmark::DoNotOptimize(eig.eigenvalues());
  }
}
BENCHMARK(BM_ContactEigenvalues_EigenQr);

}  // namespace
