#include "offline/sim/twin_linear_algebra.hpp"

#include <cmath>
#include <limits>
#include <utility>

namespace tpf::offline {

namespace {

// Σ term(k), k = 0 … count − 1, term after term (Eigen's loops at run-time sizes); 0 when empty.
template <typename Term>
double sum_in_sequence(int count, const Term& term) {
  if (count == 0) return 0.0;
  double s = term(0);
  for (int k = 1; k < count; ++k)
    s += term(k);
  return s;
}

}  // namespace

TwinVector multiply(const TwinMatrix& a, const TwinVector& x) {
  TwinVector y(a.rows());
  multiply(a, x, y);
  return y;
}

void multiply(const TwinMatrix& a, const TwinVector& x, TwinVector& out) {
  out.resize(a.rows());
  for (Eigen::Index i = 0; i < a.rows(); ++i)
    out[i] = sum_in_sequence(static_cast<int>(a.cols()), [&](int k) { return a(i, k) * x[k]; });
}

Vector3<double> multiply(const TwinJacobian& jacobian, const TwinVector& x) {
  const int n = static_cast<int>(jacobian.cols());
  Vector3<double> y;
  // Eigen fills rows 0 and 1 as one packet, adding column after column, and row 2 on its own
  // by an unrolled sum over the row.
  for (int r = 0; r < 2; ++r)
    y[r] = sum_in_sequence(n, [&](int k) { return jacobian(r, k) * x[k]; });
  y[2] = sum_in_halves(0, n, [&](int k) { return jacobian(2, k) * x[k]; });
  return y;
}

TwinVector multiply_transposed(const TwinJacobian& jacobian, const Vector3<double>& f) {
  TwinVector y(jacobian.cols());
  multiply_transposed(jacobian, f, y);
  return y;
}

void multiply_transposed(const TwinJacobian& jacobian, const Vector3<double>& f, TwinVector& out) {
  out.resize(jacobian.cols());
  for (Eigen::Index j = 0; j < jacobian.cols(); ++j)
    out[j] = sum_in_lanes(0, 3, [&](int r) { return jacobian(r, j) * f[r]; });
}

bool TwinCholesky::compute(const TwinMatrix& a) {
  factor_ = a;
  TwinMatrix& m = factor_;
  const int n = static_cast<int>(m.rows());
  for (int k = 0; k < n; ++k) {
    double x = m(k, k);
    if (k > 0) x -= sum_in_sequence(k, [&](int j) { return m(k, j) * m(k, j); });
    if (x <= 0.0) return false;
    m(k, k) = x = std::sqrt(x);
    for (int i = k + 1; i < n; ++i) {
      if (k > 0) m(i, k) -= sum_in_sequence(k, [&](int j) { return m(i, j) * m(k, j); });
      m(i, k) /= x;
    }
  }
  return true;
}

void TwinCholesky::solve_in_place(TwinVector& b) const {
  const TwinMatrix& m = factor_;
  const int n = static_cast<int>(m.rows());
  for (int i = 0; i < n; ++i) {  // L·y = b: a row of L is strided, summed in halves
    if (i > 0) b[i] -= sum_in_halves(0, i, [&](int k) { return m(i, k) * b[k]; });
    b[i] /= m(i, i);
  }
  for (int i = n - 1; i >= 0; --i) {  // Lᵀ·x = y: a column of L is contiguous, summed in lanes
    if (i < n - 1) b[i] -= sum_in_lanes(i + 1, n - 1 - i, [&](int k) { return m(k, i) * b[k]; });
    b[i] /= m(i, i);
  }
}

void TwinLdlt::compute(const TwinMatrix& a) {
  factor_ = a;
  TwinMatrix& m = factor_;
  const int n = static_cast<int>(m.rows());
  transpositions_.assign(static_cast<std::size_t>(n), 0);
  for (int k = 0; k < n; ++k)
    transpositions_[static_cast<std::size_t>(k)] = k;
  if (n <= 1) return;
  temp_.resize(n);
  TwinVector& temp = temp_;
  for (int k = 0; k < n; ++k) {
    int biggest = k;  // the first of the largest |D| in the trailing corner
    for (int i = k + 1; i < n; ++i)
      if (std::abs(m(i, i)) > std::abs(m(biggest, biggest))) biggest = i;
    transpositions_[static_cast<std::size_t>(k)] = biggest;
    if (biggest != k) {  // swap k and `biggest` in the lower triangle
      for (int j = 0; j < k; ++j)
        std::swap(m(k, j), m(biggest, j));
      for (int i = biggest + 1; i < n; ++i)
        std::swap(m(i, k), m(i, biggest));
      std::swap(m(k, k), m(biggest, biggest));
      for (int i = k + 1; i < biggest; ++i)
        std::swap(m(i, k), m(biggest, i));
    }
    if (k > 0) {
      for (int j = 0; j < k; ++j)
        temp[j] = m(j, j) * m(k, j);
      m(k, k) -= sum_in_sequence(k, [&](int j) { return m(k, j) * temp[j]; });
      for (int i = k + 1; i < n; ++i)
        m(i, k) -= sum_in_sequence(k, [&](int j) { return m(i, j) * temp[j]; });
    }
    const double pivot = m(k, k);
    if (k == 0 && !(std::abs(pivot) > 0.0)) {  // a zero diagonal: nothing to factor
      for (int j = 0; j < n; ++j)
        transpositions_[static_cast<std::size_t>(j)] = j;
      return;
    }
    if (std::abs(pivot) > 0.0)
      for (int i = k + 1; i < n; ++i)
        m(i, k) /= pivot;
  }
}

TwinVector TwinLdlt::solve(const TwinVector& b) const {
  TwinVector x = b;
  solve_in_place(x);
  return x;
}

void TwinLdlt::solve_in_place(TwinVector& x) const {
  const TwinMatrix& m = factor_;
  const int n = static_cast<int>(m.rows());
  for (int k = 0; k < n; ++k)  // P·b
    std::swap(x[k], x[transpositions_[static_cast<std::size_t>(k)]]);
  for (int i = 1; i < n; ++i)  // unit L, rows summed in halves
    x[i] -= sum_in_halves(0, i, [&](int k) { return m(i, k) * x[k]; });
  for (int i = 0; i < n; ++i)  // D⁺
    x[i] = std::abs(m(i, i)) > std::numeric_limits<double>::min() ? x[i] / m(i, i) : 0.0;
  for (int i = n - 2; i >= 0; --i)  // unit Lᵀ, columns summed in lanes
    x[i] -= sum_in_lanes(i + 1, n - 1 - i, [&](int k) { return m(k, i) * x[k]; });
  for (int k = n - 1; k >= 0; --k)  // Pᵀ
    std::swap(x[k], x[transpositions_[static_cast<std::size_t>(k)]]);
}

}  // namespace tpf::offline
