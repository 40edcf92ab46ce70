#include "wave_analysis.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

namespace talus::writers {

WaveStatistics zero_up_crossing(std::span<const double> time, std::span<const double> elevation, double from) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> t, eta;
  for (std::size_t k = 0; k < time.size() && k < elevation.size(); ++k)
    if (time[k] >= from && std::isfinite(elevation[k])) {
      t.push_back(time[k]);
      eta.push_back(elevation[k]);
    }
  WaveStatistics s{0, nan, nan, nan, nan, {}};
  if (eta.size() < 3) return s;
  double sum = 0.0;
  for (double e : eta) sum += e;
  s.mean_level = sum / static_cast<double>(eta.size());

  double last_crossing = nan, crest = -std::numeric_limits<double>::infinity(), trough = -crest;
  double height_sum = 0.0, period_sum = 0.0, max_height = 0.0;
  for (std::size_t k = 0; k + 1 < eta.size(); ++k) {
    crest = std::max(crest, eta[k]);
    trough = std::min(trough, eta[k]);
    const double a = eta[k] - s.mean_level, b = eta[k + 1] - s.mean_level;
    if (!(a < 0.0 && b >= 0.0)) continue;
    const double crossing = t[k] + (t[k + 1] - t[k]) * (-a) / (b - a);
    s.crossings.push_back(crossing);
    if (std::isfinite(last_crossing)) {
      const double height = crest - trough;
      height_sum += height;
      period_sum += crossing - last_crossing;
      max_height = std::max(max_height, height);
      ++s.waves;
    }
    last_crossing = crossing;
    crest = -std::numeric_limits<double>::infinity();
    trough = -crest;
  }
  if (s.waves == 0) return s;
  s.height = height_sum / static_cast<double>(s.waves);
  s.max_height = max_height;
  s.period = period_sum / static_cast<double>(s.waves);
  return s;
}

std::string breaker_type(double xi) {
  if (!std::isfinite(xi)) return "unknown";
  if (xi > 2.0) return "surging_or_collapsing";
  if (xi >= 0.4) return "plunging";
  return "spilling";
}

double linear_wavelength(double period, double depth, double g) {
  if (!(period > 0.0 && depth > 0.0) || !std::isfinite(period) || !std::isfinite(depth))
    return std::numeric_limits<double>::quiet_NaN();
  const double omega2 = std::pow(2.0 * std::numbers::pi / period, 2);
  // k g tanh(k d) rises with k; the root lies between the deep-water k (tanh < 1) and omega^2 / (g tanh(k_deep d)).
  double lo = omega2 / g, hi = omega2 / (g * std::tanh(lo * depth));
  for (int it = 0; it < 200 && hi - lo > 1e-15 * hi; ++it) {
    const double mid = 0.5 * (lo + hi);
    (g * mid * std::tanh(mid * depth) < omega2 ? lo : hi) = mid;
  }
  const double k = 0.5 * (lo + hi);
  return 2.0 * std::numbers::pi / k;
}

BreakerNumbers breaker_numbers(double surf_height, double offshore_height, double period, double slope_degrees,
                               double water_depth, double g) {
  BreakerNumbers n;
  const double alpha = std::tan(slope_degrees * std::numbers::pi / 180.0);
  n.wavelength = g * period * period / (2.0 * std::numbers::pi);
  n.iribarren = alpha / std::sqrt(surf_height / n.wavelength);
  n.froude = (offshore_height / n.wavelength) * water_depth * (1.0 / period) / std::sqrt(g / alpha);
  n.type = breaker_type(n.iribarren);
  return n;
}

}  // namespace talus::writers
