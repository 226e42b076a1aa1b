// sin and cos of one angle together, for joint rotations: the cost of a few multiply-adds.
#pragma once

#include <cmath>

namespace tpf {

/// sin x and cos x in double precision, within an ulp or so of std::sin and std::cos (tested
/// against them): x is reduced to r = x − k·π/2, |r| ≤ π/4, with π/2 in two parts (exact for
/// |x| < 1e5), then fdlibm's minimax polynomials for sin and cos on [−π/4, π/4]; the quadrant k
/// picks signs and swaps. sin 0 = 0 and cos 0 = 1 exactly. Larger or non-finite x fall back to
/// std::sin/std::cos. No branches on the normal path but the quadrant's, no library call: several
/// times cheaper than the library's sincos for joint angles, which dominated the kinematics.
inline void sin_cos(double x, double& sine, double& cosine) noexcept {
  if (!(std::abs(x) < 1e5)) {
    sine = std::sin(x);
    cosine = std::cos(x);
    return;
  }
  constexpr double two_over_pi = 6.36619772367581382433e-01;
  constexpr double pi_over_2_high = 1.57079632673412561417e+00;  // first 33 bits of π/2
  constexpr double pi_over_2_low = 6.07710050650619224932e-11;   // π/2 − pi_over_2_high
  constexpr double round_magic = 6755399441055744.0;             // 1.5·2⁵²: rounds to integer
  const double k = (x * two_over_pi + round_magic) - round_magic;
  const double r = (x - k * pi_over_2_high) - k * pi_over_2_low;
  const double z = r * r;
  const double s =
      r + r * z *
              (-1.66666666666666324348e-01 +
               z * (8.33333333332248946124e-03 +
                    z * (-1.98412698298579493134e-04 +
                         z * (2.75573137070700676789e-06 + z * (-2.50507602534068634195e-08 +
                                                                z * 1.58969099521155010221e-10)))));
  const double c =
      1.0 - 0.5 * z +
      z * z *
          (4.16666666666666019037e-02 +
           z * (-1.38888888888741095749e-03 +
                z * (2.48015872894767294178e-05 +
                     z * (-2.75573143513906633035e-07 +
                          z * (2.08757232129817482790e-09 + z * -1.13596475577881948265e-11)))));
  switch (static_cast<long long>(k) & 3) {
    case 0:
      sine = s, cosine = c;
      break;
    case 1:
      sine = c, cosine = -s;
      break;
    case 2:
      sine = -s, cosine = -c;
      break;
    default:
      sine = -c, cosine = s;
      break;
  }
}

/// The float form: computed in double, rounded once.
inline void sin_cos(float x, float& sine, float& cosine) noexcept {
  double s, c;
  sin_cos(static_cast<double>(x), s, c);
  sine = static_cast<float>(s);
  cosine = static_cast<float>(c);
}

}  // namespace tpf
