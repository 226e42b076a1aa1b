// The twin's dense linear algebra at run-time size, in the order of operations of Eigen's
// fixed-size kernels (Eigen 3.4, default SIMD: SSE2 packets of two doubles, no FMA).
//
// A rounding difference of one ulp anywhere in a step grows, through the drive's quantised
// position and current, into a different log within seconds. The twin's logs must not depend on
// how its vectors are sized, and Eigen rounds a product or a solve differently at run-time sizes
// (general matrix-vector kernels and blocked triangular solves, summing term after term) than at
// a fixed size of at most 8 (complete unrolling, summing in halves or in SIMD lanes). The solves
// and the Jacobian products here compute at any size what Eigen computes at a fixed size of up
// to 8, and apply the same rules beyond; A·x sums term after term at every size.
// tests/sim/twin_linear_algebra_test.cpp compares them bit for bit with Eigen for 1 to 8
// unknowns.
//
// The sums, for n terms t_0 … t_{n−1}:
//   sequential:  ((t_0 + t_1) + t_2) + …                 Eigen's loops at run-time sizes
//   halves:      Σ(t_0 … t_{h−1}) + Σ(t_h … t_{n−1}), h = n/2, recursively
//   lanes:       P lanes (P = 2 doubles per SSE2 packet) summed in halves over the ⌊n/P⌋ packets,
//                the lanes added (in halves again), then the n mod P remaining terms in halves
#pragma once

#include <vector>

#include "offline/sim/scenario.hpp"

namespace tpf::offline {

/// A 3×N matrix (a pad's linear Jacobian).
using TwinJacobian = Eigen::Matrix<double, 3, Eigen::Dynamic>;

/// Σ term(k), k = first … first + count − 1, summed in halves (Eigen's unrolled scalar sum).
template <typename Term>
double sum_in_halves(int first, int count, const Term& term) {
  if (count == 1) return term(first);
  const int half = count / 2;
  return sum_in_halves(first, half, term) + sum_in_halves(first + half, count - half, term);
}

/// Σ term(k), k = first … first + count − 1, as Eigen's unrolled vectorised sum over contiguous
/// coefficients: lanes of kTwinPacketSize terms, then the remainder in halves.
template <typename Term>
double sum_in_lanes(int first, int count, const Term& term);

/// Packet width of Eigen's vectorised sums of doubles on this build (2 with SSE2).
inline constexpr int kTwinPacketSize = Eigen::internal::packet_traits<double>::size;

template <typename Term>
double sum_in_lanes(int first, int count, const Term& term) {
  int lanes = kTwinPacketSize;  // Eigen's packet for `count` terms: halved until it divides count
  while (lanes > 2 && count % lanes != 0)
    lanes /= 2;
  const int packets = count / lanes;
  if (packets == 0) return sum_in_halves(first, count, term);
  double lane[16];
  for (int l = 0; l < lanes; ++l)
    lane[l] = sum_in_halves(0, packets, [&](int p) { return term(first + p * lanes + l); });
  for (int width = lanes; width > 1; width /= 2)  // a packet's horizontal sum, in halves
    for (int l = 0; l < width / 2; ++l)
      lane[l] = lane[l] + lane[l + width / 2];
  const int rest = count - packets * lanes;
  if (rest == 0) return lane[0];
  return lane[0] + sum_in_halves(first + packets * lanes, rest, term);
}

/// A·x, each coefficient summed sequentially over the columns (an N×N matrix times a vector).
TwinVector multiply(const TwinMatrix& a, const TwinVector& x);
/// A·x into `out` (resized to A's rows: allocation-free once it has that size). `out` must not be
/// `x`.
void multiply(const TwinMatrix& a, const TwinVector& x, TwinVector& out);

/// J·x for a 3×N Jacobian, as Eigen's fixed-size Matrix<double, 3, N> times a vector of N.
Vector3<double> multiply(const TwinJacobian& jacobian, const TwinVector& x);

/// Jᵀ·f for a 3×N Jacobian, each joint's three terms summed as in Eigen's Jᵀ·f of a fixed-size J.
TwinVector multiply_transposed(const TwinJacobian& jacobian, const Vector3<double>& f);
/// Jᵀ·f into `out` (resized to N: allocation-free once it has that size).
void multiply_transposed(const TwinJacobian& jacobian, const Vector3<double>& f, TwinVector& out);

/// Cholesky factor L (A = L·Lᵀ) of a symmetric positive definite matrix and solves with it, as
/// Eigen::LLT of a fixed-size matrix. Only the lower triangle of A is read.
class TwinCholesky {
 public:
  /// Factors A; false (and the factor unusable) when A is not positive definite. Allocation-free
  /// from the second call at the same size on.
  bool compute(const TwinMatrix& a);
  /// x = A⁻¹·b in place.
  void solve_in_place(TwinVector& b) const;

 private:
  TwinMatrix factor_;
};

/// A = Pᵀ·L·D·Lᵀ·P with diagonal pivoting, as Eigen::LDLT of a fixed-size matrix (solves a
/// symmetric matrix that is only semi-definite too). Only the lower triangle of A is read.
class TwinLdlt {
 public:
  /// Factors A; allocation-free from the second call at the same size on.
  void compute(const TwinMatrix& a);
  /// A⁻¹·b (the pseudo-inverse of D where a pivot is zero).
  TwinVector solve(const TwinVector& b) const;
  /// b ← A⁻¹·b, as solve(b) and allocation-free.
  void solve_in_place(TwinVector& b) const;

 private:
  TwinMatrix factor_;                ///< L below the diagonal, D on it
  std::vector<int> transpositions_;  ///< row k was swapped with row transpositions_[k]
  TwinVector temp_;                  ///< compute's workspace: D·(row k of L)
};

}  // namespace tpf::offline
