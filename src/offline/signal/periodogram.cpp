#include "offline/signal/periodogram.hpp"

#include <algorithm>
#include <cmath>
#include <complex>

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

PhaseSums phase_sums(const CentredResidual& c, const Eigen::ArrayXd& re, const Eigen::ArrayXd& im) {
  return {{re.sum(), im.sum()},
          {(c.u * re).sum(), (c.u * im).sum()},
          {(c.r * re).sum(), (c.r * im).sum()},
          {(re.square() - im.square()).sum(), 2 * (re * im).sum()}};
}

PhaseSums exact_phase_sums(const CentredResidual& c, double n, double scale) {
  const Eigen::ArrayXd theta = n * scale * c.u;
  return phase_sums(c, theta.cos(), theta.sin());
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

double dominant_cycles(const Eigen::VectorXd& q, const Eigen::VectorXd& r, int lo, int hi,
                       double scale) {
  double best = 0, best_power = -1;
  for (int n = lo; n <= hi; ++n) {
    std::complex<double> sum = 0;
    for (Eigen::Index k = 0; k < q.size(); ++k)
      sum += r[k] * std::polar(1.0, -n * scale * q[k]);
    if (std::norm(sum) > best_power) {
      best_power = std::norm(sum);
      best = n;
    }
  }
  return best;
}

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
  const Eigen::ArrayXd wr = advance.cos(), wi = advance.sin();
  Eigen::ArrayXd re(m), im(m), next(m);
  Eigen::Index best = 0;
  double best_sum = -1;
  for (Eigen::Index i = 0; i < points; ++i) {
    if (i % 64 == 0) {
      const Eigen::ArrayXd theta = (lo + static_cast<double>(i) * step) * scale * c.u;
      re = theta.cos();
      im = theta.sin();
    } else {
      next = re * wr - im * wi;
      im = re * wi + im * wr;
      re = next;
    }
    const double e = explained_sum(phase_sums(c, re, im), samples, c);
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

}  // namespace tpf::offline
