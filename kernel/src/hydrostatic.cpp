#include "talus/hydrostatic.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace talus {

namespace {

// One particle's part in one column: 16 bytes, four per particle in 3D (a
// footprint off the columns' grid overlaps two along each axis), which made
// this the peak of a run's set-up; the height and the covered fraction are
// recomputed from the position where needed.
struct Share {
  std::int64_t column;
  std::size_t particle;
};

// Unit vectors normal to `up` spanning the scene's horizontal directions (one in 2D).
void horizontal_axes(const Vec3& up, int dim, Vec3& e1, Vec3& e2) {
  if (dim == 2) {
    e1 = Vec3{up.y, -up.x, 0.0};
    e2 = Vec3{};
  } else {
    e1 = cross(up, std::abs(up.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0});
    e2 = cross(up, e1 / norm(e1));
  }
  e1 = e1 / norm(e1);
}

// The length of column [k w, (k + 1) w) that [c - s/2, c + s/2] overlaps.
double overlap(double c, double s, double w, std::int64_t k) {
  const double lo = c - 0.5 * s, hi = c + 0.5 * s;
  return std::min(hi, (k + 1) * w) - std::max(lo, k * w);
}

// The columns that [c - s/2, c + s/2] overlaps.
template <class F>
void overlaps(double c, double s, double w, F&& f) {
  for (auto k = static_cast<std::int64_t>(std::floor((c - 0.5 * s) / w)); k * w < c + 0.5 * s; ++k)
    if (overlap(c, s, w, k) > 1e-9 * w) f(k);
}

}  // namespace

std::vector<double> hydrostatic_pressure(std::span<const Vec3> position, std::span<const double> spacing,
                                         std::span<const double> density, Vec3 gravity, int dim) {
  const std::size_t n = position.size();
  std::vector<double> p(n, 0.0);
  const double g = norm(gravity);
  if (n == 0 || !(g > 0.0)) return p;
  const Vec3 up = gravity * (-1.0 / g);
  Vec3 e1, e2;
  horizontal_axes(up, dim, e1, e2);
  const double w = *std::min_element(spacing.begin(), spacing.end());

  // 2^32 columns per row: more than any scene has across one axis.
  constexpr std::int64_t row = std::int64_t{1} << 32;
  auto height = [&](const Share& a) { return dot(position[a.particle], up); };
  // The part of column a.column's cross-section that a's footprint covers.
  auto fraction = [&](const Share& a) {
    const Vec3& x = position[a.particle];
    const double s = spacing[a.particle];
    if (dim == 2) return overlap(dot(x, e1), s, w, a.column) / w;
    const std::int64_t ku = (a.column + row / 2) >> 32;  // floor division: kv lies in [-2^31, 2^31)
    const std::int64_t kv = a.column - ku * row;
    return overlap(dot(x, e1), s, w, ku) * overlap(dot(x, e2), s, w, kv) / (w * w);
  };
  std::vector<Share> shares;
  shares.reserve(n * (dim == 3 ? 4 : 2));
  for (std::size_t i = 0; i < n; ++i) {
    const double s = spacing[i];
    overlaps(dot(position[i], e1), s, w, [&](std::int64_t ku) {
      if (dim == 2) {
        shares.push_back({ku, i});
        return;
      }
      overlaps(dot(position[i], e2), s, w, [&](std::int64_t kv) { shares.push_back({ku * row + kv, i}); });
    });
  }
  std::sort(shares.begin(), shares.end(), [&](const Share& a, const Share& b) {
    return a.column != b.column ? a.column < b.column : height(a) > height(b);
  });

  // Down each column, layer by layer (shares within half the finest spacing in height). A layer adds its
  // coverage-weighted mean of rho s, so a column the bodies cover only in part is not diluted.
  std::vector<double> weighted(n, 0.0), covered(n, 0.0);
  for (std::size_t a = 0; a < shares.size();) {
    double above = 0.0;                 // mass per unit area above the current layer
    double previous_bottom = HUGE_VAL;  // the first layer is under a free surface
    std::size_t b = a;
    while (b < shares.size() && shares[b].column == shares[a].column) {
      std::size_t e = b;
      double top = -HUGE_VAL, bottom = HUGE_VAL, mass = 0.0, cover = 0.0;
      const double layer_top = height(shares[b]);
      for (; e < shares.size() && shares[e].column == shares[b].column && layer_top - height(shares[e]) < 0.5 * w;
           ++e) {
        const double s = spacing[shares[e].particle], h = height(shares[e]), f = fraction(shares[e]);
        top = std::max(top, h + 0.5 * s);
        bottom = std::min(bottom, h - 0.5 * s);
        mass += density[shares[e].particle] * s * f;
        cover += f;
      }
      if (previous_bottom - top > 0.5 * w) above = 0.0;  // an air gap: a new free surface
      const double layer = mass / cover;
      for (std::size_t k = b; k < e; ++k) {
        const double f = fraction(shares[k]);
        weighted[shares[k].particle] += f * g * (above + 0.5 * layer);
        covered[shares[k].particle] += f;
      }
      above += layer;
      previous_bottom = bottom;
      b = e;
    }
    a = b;
  }
  for (std::size_t i = 0; i < n; ++i) p[i] = weighted[i] / covered[i];
  return p;
}

}  // namespace talus
