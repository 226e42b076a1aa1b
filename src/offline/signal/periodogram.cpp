#include "offline/signal/periodogram.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <vector>

#include "offline/common/eigen_order_kernels.hpp"

namespace tpf::offline {
namespace {

/// q centred (u) and r with its offset and slope in q removed: what the sin/cos are fitted to.
struct CentredResidual {
  Eigen::ArrayXd u, r;
  double uu = 0;  ///< Σ u²
  double rr = 0;  ///< Σ r², r without its offset and slope
};

CentredResidual centred_residual(const Eigen::VectorXd& q, const Eigen::VectorXd& r) {
  CentredResidual c;
  c.u = q.array() - q.mean();
  c.uu = c.u.square().sum();
  c.r = r.array() - r.mean();
  if (c.uu > 0) c.r -= (c.u * c.r).sum() / c.uu * c.u;
  c.rr = c.r.square().sum();
  return c;
}

/// Sums over the samples of z = e^(iθ) (θ = n·scale·u), u·z, r·z and z²: all the least-squares
/// fit of cos θ, sin θ beside an offset and a slope needs.
struct PhaseSums {
  std::complex<double> z, uz, rz, zz;
};

PhaseSums eigen_phase_sums(const CentredResidual& c, const Eigen::ArrayXd& re,
                           const Eigen::ArrayXd& im) {
  return {{re.sum(), im.sum()},
          {(c.u * re).sum(), (c.u * im).sum()},
          {(c.r * re).sum(), (c.r * im).sum()},
          {(re.square() - im.square()).sum(), 2 * (re * im).sum()}};
}

#if TPF_EIGEN_ORDER_AVX

// The kernel whose order is reproduced: 2-double packets, two of them per step.
constexpr bool kSumOrderKnown = Eigen::internal::packet_traits<double>::size == 2 &&
                                !Eigen::internal::packet_traits<double>::HasHalfPacket;

/// One sum of fused_phase_sums: its four lanes, and its terms of the `rest` (< 4) samples after
/// them, added as Eigen's sum() adds them.
__attribute__((target("avx"))) double total(__m256d lanes, const double* tail, Eigen::Index rest) {
  alignas(32) double l[4];
  _mm256_store_pd(l, lanes);
  double p0 = l[0] + l[2], p1 = l[1] + l[3];
  if (rest >= 2) {
    p0 += tail[0];
    p1 += tail[1];
  }
  double sum = p0 + p1;
  if (rest == 1) sum += tail[0];
  if (rest == 3) sum += tail[2];
  return sum;
}

/// The eight sums of eigen_phase_sums in one pass over the samples (with `rotate`, each e^(iθ)
/// first advanced by w = wr + i·wi in place, as fitted_cycles' step does it), each added in the
/// order Eigen's SSE2 sum() adds it: four lanes (the samples k mod 4 of the whole quadruples),
/// lanes 0 + 2 and 1 + 3, the next pair, the two lanes, the last odd sample. Bit for bit Eigen's.
__attribute__((target("avx"))) PhaseSums fused_phase_sums(const CentredResidual& c, double* re,
                                                          double* im, const double* wr,
                                                          const double* wi, bool rotate) {
  const Eigen::Index m = c.u.size();
  const double* u = c.u.data();
  const double* r = c.r.data();
  const Eigen::Index quads = m / 4 * 4;
  __m256d z_re = _mm256_setzero_pd(), z_im = z_re, uz_re = z_re, uz_im = z_re, rz_re = z_re,
          rz_im = z_re, zz_re = z_re, zz_im = z_re;
  for (Eigen::Index k = 0; k < quads; k += 4) {
    __m256d a = _mm256_loadu_pd(re + k), b = _mm256_loadu_pd(im + k);
    if (rotate) {
      const __m256d cw = _mm256_loadu_pd(wr + k), sw = _mm256_loadu_pd(wi + k);
      const __m256d next = _mm256_sub_pd(_mm256_mul_pd(a, cw), _mm256_mul_pd(b, sw));
      b = _mm256_add_pd(_mm256_mul_pd(a, sw), _mm256_mul_pd(b, cw));
      a = next;
      _mm256_storeu_pd(re + k, a);
      _mm256_storeu_pd(im + k, b);
    }
    const __m256d uk = _mm256_loadu_pd(u + k), rk = _mm256_loadu_pd(r + k);
    z_re = _mm256_add_pd(z_re, a);
    z_im = _mm256_add_pd(z_im, b);
    uz_re = _mm256_add_pd(uz_re, _mm256_mul_pd(uk, a));
    uz_im = _mm256_add_pd(uz_im, _mm256_mul_pd(uk, b));
    rz_re = _mm256_add_pd(rz_re, _mm256_mul_pd(rk, a));
    rz_im = _mm256_add_pd(rz_im, _mm256_mul_pd(rk, b));
    zz_re = _mm256_add_pd(zz_re, _mm256_sub_pd(_mm256_mul_pd(a, a), _mm256_mul_pd(b, b)));
    zz_im = _mm256_add_pd(zz_im, _mm256_mul_pd(a, b));
  }
  // The samples after the quadruples, each sum's terms of them.
  double tail[8][3] = {};
  for (Eigen::Index k = quads; k < m; ++k) {
    if (rotate) {
      const double next = re[k] * wr[k] - im[k] * wi[k];
      im[k] = re[k] * wi[k] + im[k] * wr[k];
      re[k] = next;
    }
    const double a = re[k], b = im[k];
    const double terms[8] = {a, b, u[k] * a, u[k] * b, r[k] * a, r[k] * b, a * a - b * b, a * b};
    for (int q = 0; q < 8; ++q)
      tail[q][k - quads] = terms[q];
  }
  const Eigen::Index rest = m - quads;
  return {{total(z_re, tail[0], rest), total(z_im, tail[1], rest)},
          {total(uz_re, tail[2], rest), total(uz_im, tail[3], rest)},
          {total(rz_re, tail[4], rest), total(rz_im, tail[5], rest)},
          {total(zz_re, tail[6], rest), 2 * total(zz_im, tail[7], rest)}};
}

/// Whether fused_phase_sums runs here (the CPU has AVX, Eigen sums as assumed, enough samples
/// for Eigen's two-packet loop).
bool fused_sums_run(Eigen::Index m) {
  return kSumOrderKnown && m >= 8 && cpu_runs_eigen_order_kernels();
}

#endif  // TPF_EIGEN_ORDER_AVX

PhaseSums phase_sums(const CentredResidual& c, Eigen::ArrayXd& re, Eigen::ArrayXd& im) {
#if TPF_EIGEN_ORDER_AVX
  if (fused_sums_run(c.u.size()))
    return fused_phase_sums(c, re.data(), im.data(), nullptr, nullptr, false);
#endif
  return eigen_phase_sums(c, re, im);
}

/// e^(iθ) advanced by w = wr + i·wi, then its phase sums.
PhaseSums rotated_phase_sums(const CentredResidual& c, Eigen::ArrayXd& re, Eigen::ArrayXd& im,
                             const Eigen::ArrayXd& wr, const Eigen::ArrayXd& wi,
                             Eigen::ArrayXd& next) {
#if TPF_EIGEN_ORDER_AVX
  if (fused_sums_run(c.u.size()))
    return fused_phase_sums(c, re.data(), im.data(), wr.data(), wi.data(), true);
#endif
  next = re * wr - im * wi;
  im = re * wi + im * wr;
  re = next;
  return eigen_phase_sums(c, re, im);
}

/// re = cos θ, im = sin θ per sample: on glibc from one sincos call each (the values its sin and
/// cos give, in one call instead of two), elsewhere from std::cos and std::sin.
void phases(const Eigen::ArrayXd& theta, Eigen::ArrayXd& re, Eigen::ArrayXd& im) {
  re.resize(theta.size());
  im.resize(theta.size());
  for (Eigen::Index k = 0; k < theta.size(); ++k) {
#if defined(__GLIBC__)
    ::sincos(theta[k], &im[k], &re[k]);
#else
    re[k] = std::cos(theta[k]);
    im[k] = std::sin(theta[k]);
#endif
  }
}

PhaseSums exact_phase_sums(const CentredResidual& c, double n, double scale) {
  const Eigen::ArrayXd theta = n * scale * c.u;
  Eigen::ArrayXd re, im;
  phases(theta, re, im);
  return phase_sums(c, re, im);
}

/// The sum of squares of r that cos θ and sin θ explain beside an offset and a slope in q: b'G⁻¹b,
/// G the Gram of the two columns with the offset and slope projected out, b their products with
/// r (already without them). One column where the two are (numerically) collinear.
double explained_sum(const PhaseSums& p, double m, const CentredResidual& c) {
  const double sum_c = p.z.real(), sum_s = p.z.imag();
  double gcc = 0.5 * (m + p.zz.real()) - sum_c * sum_c / m;
  double gss = 0.5 * (m - p.zz.real()) - sum_s * sum_s / m;
  double gsc = 0.5 * p.zz.imag() - sum_s * sum_c / m;
  if (c.uu > 0) {
    gcc -= p.uz.real() * p.uz.real() / c.uu;
    gss -= p.uz.imag() * p.uz.imag() / c.uu;
    gsc -= p.uz.real() * p.uz.imag() / c.uu;
  }
  const double rc = p.rz.real(), rs = p.rz.imag();
  const double tiny = 1e-12 * m;
  const double det = gcc * gss - gsc * gsc;
  double e = 0;
  if (det > tiny * m)
    e = (rc * rc * gss - 2 * rc * rs * gsc + rs * rs * gcc) / det;
  else
    e = std::max(gcc > tiny ? rc * rc / gcc : 0.0, gss > tiny ? rs * rs / gss : 0.0);
  return std::clamp(e, 0.0, c.rr);
}

}  // namespace

double fitted_cycles(const Eigen::VectorXd& q, const Eigen::VectorXd& r, double lo, double hi,
                     double scale) {
  const Eigen::Index m = q.size();
  if (m < 3 || r.size() != m || !(hi >= lo) || !(lo > 0)) return 0;
  const double span = std::abs(scale) * (q.maxCoeff() - q.minCoeff());
  if (!(span > 0)) return 0;
  const CentredResidual c = centred_residual(q, r);
  const double samples = static_cast<double>(m);
  // The grid: 1/6 of the spectral width 2π/span, so that its best point lies on the peak's lobe.
  const double width = 2 * M_PI / span;
  const Eigen::Index points = std::clamp<Eigen::Index>(
      static_cast<Eigen::Index>(std::ceil(6 * (hi - lo) / width)) + 1, 2, 8192);
  const double step = (hi - lo) / static_cast<double>(points - 1);
  // e^(iθ) per sample, advanced by e^(i·step·scale·u) from one grid point to the next and
  // computed afresh every 64 points (the rounding of the products stays ~1e-14).
  const Eigen::ArrayXd advance = step * scale * c.u;
  Eigen::ArrayXd wr, wi;
  phases(advance, wr, wi);
  Eigen::ArrayXd re(m), im(m), next(m);
  Eigen::Index best = 0;
  double best_sum = -1;
  for (Eigen::Index i = 0; i < points; ++i) {
    PhaseSums sums;
    if (i % 64 == 0) {
      const Eigen::ArrayXd theta = (lo + static_cast<double>(i) * step) * scale * c.u;
      phases(theta, re, im);
      sums = phase_sums(c, re, im);
    } else {
      sums = rotated_phase_sums(c, re, im, wr, wi, next);
    }
    const double e = explained_sum(sums, samples, c);
    if (e > best_sum) {
      best_sum = e;
      best = i;
    }
  }
  // Golden-section search for the maximum between the best point's neighbours.
  const auto criterion = [&](double n) {
    return explained_sum(exact_phase_sums(c, n, scale), samples, c);
  };
  const double centre = lo + static_cast<double>(best) * step;
  double a = std::max(lo, centre - step), b = std::min(hi, centre + step);
  const double ratio = (std::sqrt(5.0) - 1) / 2;
  double x1 = b - ratio * (b - a), x2 = a + ratio * (b - a);
  double f1 = criterion(x1), f2 = criterion(x2);
  for (int iteration = 0; iteration < 40 && b - a > 1e-7 * width; ++iteration) {
    if (f1 >= f2) {
      b = x2;
      x2 = x1;
      f2 = f1;
      x1 = b - ratio * (b - a);
      f1 = criterion(x1);
    } else {
      a = x1;
      x1 = x2;
      f1 = f2;
      x2 = a + ratio * (b - a);
      f2 = criterion(x2);
    }
  }
  const double refined = f1 >= f2 ? x1 : x2;
  return std::max(f1, f2) >= best_sum ? refined : centre;
}

double explained_share(const Eigen::VectorXd& q, const Eigen::VectorXd& r, double n, double scale) {
  if (q.size() < 3 || r.size() != q.size()) return 0;
  const CentredResidual c = centred_residual(q, r);
  if (!(c.rr > 0)) return 0;
  return explained_sum(exact_phase_sums(c, n, scale), static_cast<double>(q.size()), c) / c.rr;
}

int shortest_fitting_cycles(double range) {
  // Bounded before the conversion: a joint that barely moves gives 2π/range beyond any int.
  return std::max(3, static_cast<int>(std::min(std::ceil(2 * M_PI / std::max(range, 1e-9)), 1e6)));
}

double range_of_motion(const Eigen::VectorXd& q) {
  const Eigen::Index m = q.size();
  if (m < 3) return 0;
  std::vector<double> sorted(q.data(), q.data() + m);
  std::sort(sorted.begin(), sorted.end());
  return sorted[static_cast<std::size_t>(0.99 * (m - 1))] -
         sorted[static_cast<std::size_t>(0.01 * (m - 1))];
}

OutputRipple output_ripple(const Eigen::VectorXd& q, const Eigen::VectorXd& r, int highest) {
  OutputRipple out;
  out.range = range_of_motion(q);
  if (shortest_fitting_cycles(out.range) > highest) return out;
  const double lowest = std::max(3.0, M_PI / out.range);
  out.cycles = fitted_cycles(q, r, lowest, highest, 1.0);
  out.periods = out.cycles * out.range / (2 * M_PI);
  return out;
}

}  // namespace tpf::offline
