// Basal shear of a Bingham fluid in an infinite landslide (seed pfe-ie
// §2.2.2, eqs 10-13; Pastor et al. 2004, 2009). With the plug ratio
// eta = h_p / h = tau_y / tau_b and a = 6 mu v / (tau_y h), the mean speed
// v = tau_b h / (6 mu) (1 - eta)^2 (2 + eta) becomes the cubic
//   P3(eta) = eta^3 - (3 + a) eta + 2 = 0,  root sought in (0, 1].
// Pastor's quadratic approximation (seed eq. 13, whose printed form is garbled;
// valid for a in [1e-3, 1e3]):
//   P2(eta) = 3/2 eta^2 - (57/16 + a) eta + 65/32 = 0,  smaller root.
// The coefficients are those the seed's tokens show, and they are exactly the
// minimax quadratic of P3 on [0, 1] (P3 - P2 = T3(2 eta - 1)/32, |P3 - P2| <= 1/32
// for every a), which supports the reconstruction; the printed equation of
// Pastor et al. (2004, Geotechnique 54(6)) was not available to check.
#pragma once

#include <cmath>
#include <numbers>

namespace talus::rheology {

// Exact root of eta^3 - p eta + 2 = 0 (p = 3 + a >= 3) in (0, 1]. The three
// roots are real; Viete's trigonometric form gives the largest (t0) and the
// negative one (t2) without cancellation, and the product of the roots is
// -2, so the small root follows as -2 / (t0 t2), accurate for any a.
inline double bingham_plug_ratio_exact(double a) {
  if (!(a > 0.0)) return 1.0;
  const double p = 3.0 + a;
  const double s = 2.0 * std::sqrt(p / 3.0);
  const double arg = -std::pow(3.0 / p, 1.5);  // (3 q / 2 P) sqrt(-3 / P) with P = -p, q = 2
  const double phi = std::acos(arg < -1.0 ? -1.0 : arg) / 3.0;
  const double t0 = s * std::cos(phi);
  const double t2 = s * std::cos(phi - 4.0 * std::numbers::pi / 3.0);
  const double eta = -2.0 / (t0 * t2);
  return eta > 1.0 ? 1.0 : eta;
}

// Pastor's quadratic approximation: the smaller root of
// 3/2 eta^2 - (57/16 + a) eta + 65/32, in the cancellation-free form 2c / (b + sqrt(b^2 - 4 a c)).
inline double bingham_plug_ratio_pastor(double a) {
  constexpr double qa = 1.5, qc = 65.0 / 32.0;
  const double b = 57.0 / 16.0 + (a > 0.0 ? a : 0.0);
  return 2.0 * qc / (b + std::sqrt(b * b - 4.0 * qa * qc));
}

}  // namespace talus::rheology
