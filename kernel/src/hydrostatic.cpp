#include "talus/hydrostatic.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace talus {

namespace {

// One particle's part in one column.
struct Share {
  std::int64_t column;
  double height;    // of the particle's centre, along -gravity
  double fraction;  // of the column's cross-section that the particle's footprint covers
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

// The columns [k w, (k + 1) w) that [c - s/2, c + s/2] overlaps, with the overlap lengths.
template <class F>
void overlaps(double c, double s, double w, F&& f) {
  const double lo = c - 0.5 * s, hi = c + 0.5 * s;
  for (auto k = static_cast<std::int64_t>(std::floor(lo / w)); k * w < hi; ++k) {
    const double length = std::min(hi, (k + 1) * w) - std::max(lo, k * w);
    if (length > 1e-9 * w) f(k, length);
  }
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

  std::vector<Share> shares;
  shares.reserve(n * (dim == 3 ? 4 : 2));
  for (std::size_t i = 0; i < n; ++i) {
    const double s = spacing[i], h = dot(position[i], up);
    overlaps(dot(position[i], e1), s, w, [&](std::int64_t ku, double lu) {
      if (dim == 2) {
        shares.push_back({ku, h, lu / w, i});
        return;
      }
      overlaps(dot(position[i], e2), s, w, [&](std::int64_t kv, double lv) {
        // 2^32 columns per row: more than any scene has across one axis.
        shares.push_back({ku * (std::int64_t{1} << 32) + kv, h, lu * lv / (w * w), i});
      });
    });
  }
  std::sort(shares.begin(), shares.end(), [](const Share& a, const Share& b) {
    return a.column != b.column ? a.column < b.column : a.height > b.height;
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
      for (; e < shares.size() && shares[e].column == shares[b].column && shares[b].height - shares[e].height < 0.5 * w;
           ++e) {
        const double s = spacing[shares[e].particle];
        top = std::max(top, shares[e].height + 0.5 * s);
        bottom = std::min(bottom, shares[e].height - 0.5 * s);
        mass += density[shares[e].particle] * s * shares[e].fraction;
        cover += shares[e].fraction;
      }
      if (previous_bottom - top > 0.5 * w) above = 0.0;  // an air gap: a new free surface
      const double layer = mass / cover;
      for (std::size_t k = b; k < e; ++k) {
        weighted[shares[k].particle] += shares[k].fraction * g * (above + 0.5 * layer);
        covered[shares[k].particle] += shares[k].fraction;
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
