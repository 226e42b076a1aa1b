// One streaming TCN per joint behind the estimator's compensator interface (named by its kind,
// tpf::PerJointTcn<NetScalar, Hidden>, in compensator_types.hpp).
#pragma once

#include <array>
#include <cassert>
#include <type_traits>

#include "tpf/common/types.hpp"
#include "tpf/estimation/compensator.hpp"
#include "tpf/nn/tcn.hpp"

namespace tpf {

/// N independent networks Tcn<NetScalar, 5, Hidden, Levels, 4, 1> (float with bfloat16 hidden
/// taps for NetScalar = BFloat16Weights); network j sees only joint j's
/// inputs [q_j, q̇_j, q̈_j, τ̂_fric,s,j, τ_fric,nom,j] (picked from x = compensator_input(...) at j,
/// N + j, …, 4N + j) and predicts τ_TCN,j. Satisfies FrictionCompensator. Allocation-free step.
/// Large: keep on the heap (inside the estimator). N = Eigen::Dynamic: the networks live in a
/// std::vector sized by resize(joints) (start-up; the estimator calls it), and step() steps them
/// in turn (the same result, bit for bit, as step_together).
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

  /// Sizes it for `joints` joints at Eigen::Dynamic (untrained networks); at a fixed N, joints
  /// must be N and nothing changes. Start-up code.
  void resize(int joints) {
    if constexpr (N == Eigen::Dynamic) {
      networks_.clear();
      networks_.resize(static_cast<std::size_t>(joints));
      output_ = Output::Zero(joints);
    } else {
      assert(joints == N);
      (void)joints;
    }
  }
  /// The number of joints (networks).
  int joint_count() const noexcept { return static_cast<int>(networks_.size()); }

  /// τ_TCN,j = network_j(x_j) for every joint.
  /// The networks step together (Tcn::step_together: in turn with the run-time kernel or where
  /// one step already has several chains of multiply-adds, interleaved where it is a single
  /// chain): the same result as stepping each in turn, bit for bit. In turn, every other call
  /// goes from the last network to the first, so that it starts on the weights still in the L1
  /// cache (4 float 16-channel networks: ≈ 57 kB of weights against a 32 kB L1).
  const Output& step(const Input& x) noexcept {
    if constexpr (N == Eigen::Dynamic) {
      const int n = joint_count();
      for (int i = 0; i < n; ++i) {
        const int j = backwards_ ? n - 1 - i : i;
        networks_[j].step(joint_input(x, j));
        output_[j] = static_cast<S>(networks_[j].output()[0]);
      }
      backwards_ = !backwards_;
      return output_;
    } else {
      std::array<typename Network::Input, N> inputs;
      for (int j = 0; j < N; ++j)
        inputs[j] = joint_input(x, j);
      Network::step_together(networks_, inputs, backwards_);
      backwards_ = !backwards_;
      for (int j = 0; j < N; ++j)
        output_[j] = static_cast<S>(networks_[j].output()[0]);
      return output_;
    }
  }
  /// Prewarms every network with its part of the steady input x̄.
  void reset(const Input& x) noexcept {
    for (int j = 0; j < joint_count(); ++j)
      networks_[j].reset(joint_input(x, j));
  }

  Network& network(int j) noexcept { return networks_[j]; }

  /// x_j = [x_j, x_{N+j}, …, x_{4N+j}] (channel c of joint j is x_{cN+j}), in the networks'
  /// scalar.
  static typename Network::Input joint_input(const Input& x, int j) noexcept {
    using JointInput = Eigen::Matrix<S, kCompensatorInputsPerJoint, 1>;
    const Eigen::Index n = x.size() / kCompensatorInputsPerJoint;
    return Eigen::Map<const JointInput, Eigen::Unaligned, Eigen::InnerStride<N>>(
               x.data() + j, Eigen::InnerStride<N>(n))
        .template cast<Arithmetic>();
  }

 private:
  LinkArray<Network, N> networks_{};
  Output output_ = zero_or_empty<Output>();
  bool backwards_ = false;  ///< the next step goes from the last network to the first
};

}  // namespace tpf
