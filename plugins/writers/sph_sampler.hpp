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

#include <algorithm>
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

 private:
  const KernelTable* kernel_ = nullptr;
  NeighbourGrid cells_;
  std::span<const Vec3> position_;
  std::span<const double> volume_;
};

// The scans below read the fill fraction phi at a list of sample points and
// nothing else: on several MPI ranks each rank sums its own particles' share
// of phi at every sample (fill_fractions) and the ranks' sums are added before
// the scan, which then sees what one process would.

// phi at each point, from the particles bound to `sampler`.
inline void fill_fractions(const SphSampler& sampler, std::span<const Vec3> points, std::span<double> phi) {
  for (std::size_t k = 0; k < points.size(); ++k) phi[k] = sampler.fill_fraction(points[k]);
}

// The samples of the line through `at` parallel to axis `axis`, from `from`
// towards `to` in steps of `step`, starting `first` steps in.
inline std::vector<Vec3> line_samples(Vec3 at, int axis, double from, double to, double step, int first) {
  const double down = to < from ? -1.0 : 1.0;
  std::vector<Vec3> points;
  for (int k = first;; ++k) {
    const double z = from + down * k * step;
    if (down * (z - to) > 1e-12 * step) break;
    at[axis] = z;
    points.push_back(at);
  }
  return points;
}

// Free-surface elevation along a gauge line sampled by line_samples(at, axis,
// top, bottom, step, 0), scanning from `top` (the side gravity points away
// from) towards `bottom`: the first sample where phi >= threshold, placed by
// linear interpolation of phi between it and the sample before. NaN when the
// whole line is dry.
inline double surface_elevation(std::span<const Vec3> samples, std::span<const double> phi, int axis, double down,
                                double step, double threshold) {
  double above_phi = 0.0;
  for (std::size_t k = 0; k < samples.size(); ++k) {
    if (phi[k] >= threshold) {
      if (k == 0) return samples[k][axis];
      return samples[k][axis] - down * step * (phi[k] - threshold) / (phi[k] - above_phi);
    }
    above_phi = phi[k];
  }
  return std::numeric_limits<double>::quiet_NaN();
}

// What a wire wave gauge (capacitance or resistance) reads along a line
// sampled as for surface_elevation: the lowest wet point (phi >= threshold)
// plus the length of the line in water above it. The wet part of each step
// between samples is placed by linear interpolation of phi, as
// surface_elevation places the surface, so over one column of water wet from
// its foot up the two readings agree. Airborne splash adds only its own
// thickness, a crest over trapped air only its water. NaN when the whole
// line is dry.
inline double wire_elevation(std::span<const Vec3> samples, std::span<const double> phi, int axis, double down,
                             double step, double threshold) {
  // The wet length of the step between samples a and b (one of them wet).
  auto wet_part = [&](double a, double b) {
    if (a >= threshold && b >= threshold) return step;
    if (a < threshold && b < threshold) return 0.0;
    const double wet = std::max(a, b), dry = std::min(a, b);
    return step * (wet - threshold) / (wet - dry);
  };
  std::size_t lowest = samples.size();
  double length = 0.0;
  for (std::size_t k = 0; k < samples.size(); ++k) {
    if (phi[k] >= threshold) lowest = k;
    if (k > 0) length += wet_part(phi[k - 1], phi[k]);
  }
  if (lowest == samples.size()) return std::numeric_limits<double>::quiet_NaN();
  double foot = samples[lowest][axis];  // the lowest wet point: below the lowest wet sample where the next is dry
  if (lowest + 1 < samples.size()) foot += down * wet_part(phi[lowest], phi[lowest + 1]);
  return foot - down * length;
}

// Air under the free surface along the same line, sampled by
// line_samples(at, axis, surface, bottom, step, 1): scanning on down, the
// length of the first stretch where phi < threshold that has water
// (phi >= threshold) again below it: an overturning crest, a plunging jet over
// the water it falls into. Stretches shorter than `min_gap` (the dip of phi
// between close particles) and air with no water under it before the bottom
// count as none: 0.
inline double air_below(std::span<const Vec3> samples, std::span<const double> phi, int axis, double threshold,
                        double min_gap) {
  double air_from = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t k = 0; k < samples.size(); ++k) {
    const double z = samples[k][axis];
    const bool wet = phi[k] >= threshold;
    if (!wet && std::isnan(air_from)) air_from = z;
    if (wet && !std::isnan(air_from)) {
      const double gap = std::abs(z - air_from);
      if (gap >= min_gap) return gap;
      air_from = std::numeric_limits<double>::quiet_NaN();
    }
  }
  return 0.0;
}

// The samples of the segment a-b from its upper end (along `up` on axis
// `vertical`) in steps of at most `step`, for highest_wet_point.
struct SlopeLine {
  std::vector<Vec3> samples;
  Vec3 down;  // from the upper end to the lower one
};
inline SlopeLine slope_samples(Vec3 a, Vec3 b, int vertical, double up, double step) {
  if (up * (a[vertical] - b[vertical]) > 0.0) std::swap(a, b);  // b is the upper end
  SlopeLine line{{}, a - b};
  const double length = norm(line.down);
  const int samples = std::max(1, static_cast<int>(std::ceil(length / step)));
  for (int k = 0; k <= samples; ++k) line.samples.push_back(b + line.down * (static_cast<double>(k) / samples));
  return line;
}

// The vertical coordinate of the highest wet point (phi >= threshold) on a
// slope line, placed between the last dry and the first wet sample by linear
// interpolation of phi; NaN when the whole segment is dry. The run-up on a slope.
inline double highest_wet_point(const SlopeLine& line, std::span<const double> phi, int vertical, double threshold) {
  const auto segments = static_cast<double>(line.samples.size() - 1);
  double above_phi = 0.0;
  for (std::size_t k = 0; k < line.samples.size(); ++k) {
    if (phi[k] >= threshold) {  // placed by linear interpolation of phi from the dry sample before, as above
      if (k == 0) return line.samples[k][vertical];
      const double back = (phi[k] - threshold) / (phi[k] - above_phi) / segments;
      return line.samples[k][vertical] - line.down[vertical] * back;
    }
    above_phi = phi[k];
  }
  return std::numeric_limits<double>::quiet_NaN();
}

}  // namespace talus::writers
