// One streaming TCN per joint behind the estimator's compensator interface (named by its kind,
// tpf::PerJointTcn<NetScalar, Hidden>, in compensator_types.hpp).
#pragma once

#include <array>
#include <type_traits>

#include "tpf/estimation/compensator.hpp"
#include "tpf/nn/tcn.hpp"

namespace tpf {

/// N independent networks Tcn<NetScalar, 5, Hidden, Levels, 4, 1> (float with bfloat16 hidden
/// taps for NetScalar = BFloat16Weights); network j sees only joint j's
/// inputs [q_j, q̇_j, q̈_j, τ̂_fric,s,j, τ_fric,nom,j] (picked from x = compensator_input(...) at j,
/// N + j, …, 4N + j) and predicts τ_TCN,j. Satisfies FrictionCompensator. Allocation-free step.
/// Large: keep on the heap (inside the estimator).
///
/// The estimator's scalar S and the networks' NetScalar may differ: with NetScalar = float the
/// inputs are rounded to float on the way in and the outputs widened on the way out, which halves
/// the network step (twice the SIMD width) at a relative error of ≈ 1e-6 of the output;
/// NetScalar = BFloat16Weights is float with the hidden blocks' taps rounded to bfloat16, which
/// halves their bytes again (docs/tcn.md, "Precision").
template <typename S, int N, int Hidden, int Levels, typename NetScalar = S>
class PerJointTcnCompensator {
  static constexpr bool kBFloat16 = std::is_same_v<NetScalar, BFloat16Weights>;
  using Arithmetic = std::conditional_t<kBFloat16, float, NetScalar>;

 public:
  using Network = Tcn<Arithmetic, kCompensatorInputsPerJoint, Hidden, Levels, 4, 1, NetScalar>;
  using Input = CompensatorInput<S, N>;
  using Output = Eigen::Matrix<S, N, 1>;
  static constexpr int kReceptiveField = Network::kReceptiveField;

  /// τ_TCN,j = network_j(x_j) for every joint.
  /// The networks step together (Tcn::step_together: in turn with the run-time kernel or where
  /// one step already has several chains of multiply-adds, interleaved where it is a single
  /// chain): the same result as stepping each in turn, bit for bit. In turn, every other call
  /// goes from the last network to the first, so that it starts on the weights still in the L1
  /// cache (4 float 16-channel networks: ≈ 57 kB of weights against a 32 kB L1).
  const Output& step(const Input& x) noexcept {
    std::array<typename Network::Input, N> inputs;
    for (int j = 0; j < N; ++j)
      inputs[j] = joint_input(x, j);
    Network::step_together(networks_, inputs, backwards_);
    backwards_ = !backwards_;
    for (int j = 0; j < N; ++j)
      output_[j] = static_cast<S>(networks_[j].output()[0]);
    return output_;
  }
  /// Prewarms every network with its part of the steady input x̄.
  void reset(const Input& x) noexcept {
    for (int j = 0; j < N; ++j)
      networks_[j].reset(joint_input(x, j));
  }

  Network& network(int j) noexcept { return networks_[j]; }

  /// x_j = [x_j, x_{N+j}, …, x_{4N+j}] (channel c of joint j is x_{cN+j}), in the networks'
  /// scalar.
  static typename Network::Input joint_input(const Input& x, int j) noexcept {
    using JointInput = Eigen::Matrix<S, kCompensatorInputsPerJoint, 1>;
    return Eigen::Map<const JointInput, Eigen::Unaligned, Eigen::InnerStride<N>>(x.data() + j)
        .template cast<Arithmetic>();
  }

 private:
  std::array<Network, N> networks_{};
  Output output_ = Output::Zero();
  bool backwards_ = false;  ///< the next step goes from the last network to the first
};

}  // namespace tpf
