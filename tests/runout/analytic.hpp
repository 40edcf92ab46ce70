// Analytic depth profiles the run-out validation compares with.
#pragma once

#include <algorithm>
#include <cmath>

namespace talus::runout::test {

// Ritter (1892) dry-bed dam break, dam at x = 0, reservoir depth h0 on x < 0:
// h = h0 behind -c0 t, (2 c0 - x/t)^2 / (9 g) up to the front 2 c0 t, 0 beyond.
inline double ritter_depth(double x, double t, double h0, double g) {
  const double c0 = std::sqrt(g * h0);
  if (x <= -c0 * t) return h0;
  if (x >= 2.0 * c0 * t) return 0.0;
  const double s = 2.0 * c0 - x / t;
  return s * s / (9.0 * g);
}

// Mangeney et al. (2000), J. Geophys. Res. 105(B9): Coulomb dam break on an
// incline theta with friction angle delta; s along the slope, dam at s = 0,
// slope-normal depth h0 behind. With c0 = sqrt(g h0 cos theta) and
// m = g sin theta - g cos theta tan delta:
// h = (2 c0 - s/t + m t / 2)^2 / (9 g cos theta) on [-c0 t + m t^2/2, 2 c0 t + m t^2/2].
inline double mangeney_depth(double s, double t, double h0, double g, double theta, double delta) {
  const double gc = g * std::cos(theta);
  const double c0 = std::sqrt(gc * h0);
  const double m = g * std::sin(theta) - gc * std::tan(delta);
  const double shift = 0.5 * m * t * t;
  if (s <= -c0 * t + shift) return h0;
  if (s >= 2.0 * c0 * t + shift) return 0.0;
  const double q = 2.0 * c0 - s / t + 0.5 * m * t;
  return q * q / (9.0 * gc);
}

inline double mangeney_front(double t, double h0, double g, double theta, double delta) {
  const double gc = g * std::cos(theta);
  const double m = g * std::sin(theta) - gc * std::tan(delta);
  return 2.0 * std::sqrt(gc * h0) * t + 0.5 * m * t * t;
}

// Where a dam break (Ritter on a flat bed, or Mangeney's in its frame sliding
// by `shift` = m t^2 / 2) puts the material point with `volume` (per unit
// width, integral of h along the flow) ahead of it: the front holds
// (s_f - s)^3 / (27 g_n t^2) in the fan, h0 per metre behind it (g_n = g cos theta).
inline double dam_break_position(double volume, double t, double h0, double g_n, double shift = 0.0) {
  const double c0 = std::sqrt(g_n * h0);
  const double fan = c0 * c0 * c0 * t / g_n;
  if (volume <= fan) return 2.0 * c0 * t + shift - std::cbrt(volume * 27.0 * g_n * t * t);
  return -c0 * t + shift - (volume - fan) / h0;
}

}  // namespace talus::runout::test
