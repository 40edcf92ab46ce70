// SPH sampling of particle fields at arbitrary points, for probes and gauges.
//
// Shepard-normalised kernel interpolation (Shepard 1968; Monaghan 2005, Rep.
// Prog. Phys. 68, sec. 2.3):
//   f(x) = sum_j f_j V_j W(x - x_j) / sum_j V_j W(x - x_j),   V_j = m_j / rho_j
// It reproduces constants exactly everywhere and linear fields exactly where
// the particles around x are symmetric (the first moment sum_j V_j W (x_j - x)
// vanishes), e.g. at nodes and cell centres of a regular lattice in the bulk.
// The fill fraction phi(x) = sum_j V_j W(x - x_j) is ~1 inside the fluid and
// ~0.5 at a free surface; wave gauges use it.
#pragma once

#include <array>
#include <cmath>
#include <limits>
#include <span>
#include <vector>

#include "talus/neighbour_grid.hpp"
#include "talus/kernel_table.hpp"
#include "talus/vec3.hpp"

namespace talus::writers {

struct Neighbour {
  Index j;
  double weight;  // V_j W(|x - x_j|)
};

class SphSampler {
 public:
  // Once per run: the domain and the kernel.
  void configure(int dim, Vec3 lo, Vec3 hi, std::array<bool, 3> periodic, const KernelTable& kernel) {
    kernel_ = &kernel;
    cells_.configure(dim, lo, hi, kernel.support_radius(), periodic);
  }
  // Once per frame: bins the particles; `volume` is V_j per particle.
  void bind(std::span<const Vec3> position, std::span<const double> volume) {
    position_ = position;
    volume_ = volume;
    cells_.build(position);
  }

  // Neighbours of x with their weights into `out` (cleared first); returns
  // the sum of the weights, i.e. the fill fraction phi(x).
  double gather(const Vec3& x, std::vector<Neighbour>& out) const {
    out.clear();
    double sum = 0.0;
    const double radius = kernel_->support_radius();
    cells_.for_each_neighbour(x, radius, [&](Index j, const Vec3&, double r2) {
      const double w = volume_[j] * kernel_->w(std::sqrt(r2));
      out.push_back({j, w});
      sum += w;
    });
    return sum;
  }

  double fill_fraction(const Vec3& x) const {
    double sum = 0.0;
    cells_.for_each_neighbour(x, kernel_->support_radius(),
                              [&](Index j, const Vec3&, double r2) { sum += volume_[j] * kernel_->w(std::sqrt(r2)); });
    return sum;
  }

  // Calls f(j, dx, r) for every binned particle within the kernel support of
  // x, dx = x - x_j (minimum image on periodic axes).
  template <class F>
  void for_each_neighbour(const Vec3& x, F&& f) const {
    cells_.for_each_neighbour(x, kernel_->support_radius(),
                              [&](Index j, const Vec3& dx, double r2) { f(j, dx, std::sqrt(r2)); });
  }
  const KernelTable& kernel() const { return *kernel_; }

  // Shepard average of value(j) over gathered neighbours (NaN if none).
  template <class Value>
  static double shepard(const std::vector<Neighbour>& nb, double weight_sum, Value&& value) {
    if (!(weight_sum > 0.0)) return std::numeric_limits<double>::quiet_NaN();
    double acc = 0.0;
    for (const auto& n : nb) acc += n.weight * value(n.j);
    return acc / weight_sum;
  }

 private:
  const KernelTable* kernel_ = nullptr;
  NeighbourGrid cells_;
  std::span<const Vec3> position_;
  std::span<const double> volume_;
};

// Free-surface elevation along the line through `at` parallel to axis
// `axis`: scanning from `top` (the side gravity points away from; above or
// below `bottom` along the axis) towards `bottom` in steps of `step`, the
// first point where phi >= threshold, placed by linear interpolation of phi
// between it and the sample before. NaN when the whole line is dry.
inline double surface_elevation(const SphSampler& sampler, Vec3 at, int axis, double bottom, double top, double step,
                                double threshold) {
  const double down = bottom < top ? -1.0 : 1.0;
  double above_phi = 0.0;
  for (int k = 0;; ++k) {
    const double z = top + down * k * step;
    if (down * (z - bottom) > 1e-12 * step) break;
    at[axis] = z;
    const double phi = sampler.fill_fraction(at);
    if (phi >= threshold) {
      if (k == 0) return z;
      return z - down * step * (phi - threshold) / (phi - above_phi);
    }
    above_phi = phi;
  }
  return std::numeric_limits<double>::quiet_NaN();
}

// Air under the free surface at `surface` (from surface_elevation) along the
// same line: scanning on down, the length of the first stretch where
// phi < threshold that has water (phi >= threshold) again below it: an
// overturning crest, a plunging jet over the water it falls into. Stretches
// shorter than `min_gap` (the dip of phi between close particles) and air
// with no water under it before `bottom` count as none: 0.
inline double air_below(const SphSampler& sampler, Vec3 at, int axis, double surface, double bottom, double step,
                        double threshold, double min_gap) {
  const double down = bottom < surface ? -1.0 : 1.0;
  double air_from = std::numeric_limits<double>::quiet_NaN();
  for (int k = 1;; ++k) {
    const double z = surface + down * k * step;
    if (down * (z - bottom) > 1e-12 * step) return 0.0;
    at[axis] = z;
    const bool wet = sampler.fill_fraction(at) >= threshold;
    if (!wet && std::isnan(air_from)) air_from = z;
    if (wet && !std::isnan(air_from)) {
      const double gap = std::abs(z - air_from);
      if (gap >= min_gap) return gap;
      air_from = std::numeric_limits<double>::quiet_NaN();
    }
  }
}

// The vertical coordinate of the highest wet point (phi >= threshold) on the
// segment a-b, scanning in steps of `step` from its upper end (along `up` on
// axis `vertical`), placed between the last dry and the first wet sample by
// linear interpolation of phi; NaN when the whole segment is dry. The run-up
// on a slope.
inline double highest_wet_point(const SphSampler& sampler, Vec3 a, Vec3 b, int vertical, double up, double step,
                                double threshold) {
  if (up * (a[vertical] - b[vertical]) > 0.0) std::swap(a, b);  // b is the upper end
  const Vec3 d = a - b;
  const double length = std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
  const int samples = std::max(1, static_cast<int>(std::ceil(length / step)));
  double above_phi = 0.0;
  for (int k = 0; k <= samples; ++k) {
    const Vec3 at = b + d * (static_cast<double>(k) / samples);
    const double phi = sampler.fill_fraction(at);
    if (phi >= threshold) {  // placed by linear interpolation of phi from the dry sample before, as above
      if (k == 0) return at[vertical];
      const double back = (phi - threshold) / (phi - above_phi) / samples;
      return at[vertical] - d[vertical] * back;
    }
    above_phi = phi;
  }
  return std::numeric_limits<double>::quiet_NaN();
}

}  // namespace talus::writers
