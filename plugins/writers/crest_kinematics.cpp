#include "crest_kinematics.hpp"

#include <algorithm>
#include <cmath>

namespace talus::writers {

double crest_time(std::span<const double> time, std::span<const double> eta, std::size_t k) {
  if (k == 0 || k + 1 >= time.size()) return time[k];
  const double t0 = time[k - 1] - time[k], t2 = time[k + 1] - time[k];
  const double e0 = eta[k - 1] - eta[k], e2 = eta[k + 1] - eta[k];
  if (!(e0 <= 0.0 && e2 <= 0.0)) return time[k];  // NaN neighbours, or not a maximum
  // eta - eta_k = a s^2 + b s through (t0, e0), (t2, e2); vertex at -b / 2a.
  const double det = t0 * t2 * (t0 - t2);
  const double a = (e0 * t2 - e2 * t0) / det, b = (e2 * t0 * t0 - e0 * t2 * t2) / det;
  if (!(a < 0.0)) return time[k];
  return time[k] - b / (2.0 * a);
}

namespace {

// The index of the highest finite sample with time in [from, to], or npos.
std::size_t highest(std::span<const double> time, std::span<const double> eta, double from, double to) {
  std::size_t best = static_cast<std::size_t>(-1);
  for (std::size_t k = 0; k < time.size(); ++k)
    if (time[k] >= from && time[k] <= to && std::isfinite(eta[k]) && (best == static_cast<std::size_t>(-1) || eta[k] > eta[best]))
      best = k;
  return best;
}

}  // namespace

CrestKinematics crest_kinematics(std::span<const double> time, std::span<const double> eta_offshore,
                                 std::span<const double> eta_here, std::span<const double> u_here,
                                 const WaveStatistics& here, double distance, double g) {
  constexpr std::size_t none = static_cast<std::size_t>(-1);
  CrestKinematics result;
  for (std::size_t w = 0; w + 1 < here.crossings.size(); ++w) {
    const double start = here.crossings[w], end = here.crossings[w + 1];
    const std::size_t k = highest(time, eta_here, start, end);
    if (k == none) continue;
    const double crest = crest_time(time, eta_here, k);
    double u = -std::numeric_limits<double>::infinity(), trough = eta_here[k];
    for (std::size_t j = 0; j < time.size(); ++j) {
      if (!(time[j] >= start && time[j] <= end)) continue;
      if (eta_here[j] > here.mean_level && std::isfinite(u_here[j])) u = std::max(u, u_here[j]);
      if (std::isfinite(eta_here[j])) trough = std::min(trough, eta_here[j]);
    }
    const double from = crest - (end - start), to = crest;
    const std::size_t b = highest(time, eta_offshore, from, to);
    if (b == none || b == 0 || b + 1 >= time.size() || time[b - 1] < from || time[b + 1] > to)
      continue;  // the highest sample is at the window's edge: not a crest inside it (or under a sample ahead)
    const double delay = crest - crest_time(time, eta_offshore, b);
    if (!(delay > 0.0) || !std::isfinite(u)) continue;
    const double c = distance / delay;
    if (c * c < g * (eta_here[k] - trough)) {
      ++result.not_travelling;
      continue;
    }
    ++result.waves;
    if (!(u / c <= result.ratio)) {
      result.ratio = u / c;
      result.time = crest;
      result.crest_speed = c;
      result.particle_speed = u;
    }
  }
  return result;
}

}  // namespace talus::writers
