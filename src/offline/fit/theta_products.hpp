// φᵀθ_i of one feature row φ for several parameter vectors θ_i at once, bit for bit as Eigen's
// row-vector × matrix product φᵀ·[θ_1 … θ_m] gives them, in AVX registers where the CPU has
// them: the predictions of identify and diagnose (EffectDesign::predict_each).
#pragma once

#include <Eigen/Core>
#include <vector>

namespace tpf::offline {

class ThetaProducts {
 public:
  ThetaProducts() = default;
  /// `thetas`: features × m, column i = θ_i.
  explicit ThetaProducts(const Eigen::MatrixXd& thetas);

  Eigen::Index features() const { return thetas_.rows(); }
  Eigen::Index sets() const { return thetas_.cols(); }
  /// out[i] = φᵀθ_i for i < sets(), φ = phi[0 … features()). Each sum in the order of Eigen's
  /// SSE2 matrix-vector kernel (the even and the odd features apart, added, then the last of an
  /// odd count), without fused multiply-adds: equal to Eigen's product to the last bit
  /// (tests/identify/theta_products_test.cpp). For one θ (a dot product to Eigen), where Eigen is
  /// compiled with AVX or FMA (TPF_NATIVE) or where the CPU lacks AVX, Eigen's product runs.
  void apply(const double* phi, double* out) const;

 private:
  Eigen::MatrixXd thetas_;
  Eigen::Index padded_sets_ = 0;    ///< sets() rounded up to whole AVX registers (4 doubles)
  std::vector<double> by_feature_;  ///< feature-major: padded_sets_ values per feature, padded 0
};

}  // namespace tpf::offline
