// Periodic axes of the domain, for models that place or compare points across
// them: the domain's length on each periodic axis (0 on closed ones); the
// minimum image of a separation d (each periodic component in [-L/2, L/2];
// called per particle, so the periods come in precomputed); the image of p
// nearest `near`; p wrapped into [lo, hi).
#pragma once

#include <cmath>

#include "talus/vec3.hpp"
#include "talus/world.hpp"

namespace talus {

inline Vec3 periods(const World& world) {
  Vec3 period{};
  for (int a = 0; a < 3; ++a) period[a] = world.periodic[a] ? world.hi[a] - world.lo[a] : 0.0;
  return period;
}

inline Vec3 minimum_image(Vec3 d, const Vec3& period) {
  for (int a = 0; a < 3; ++a)
    if (period[a] > 0.0) d[a] -= period[a] * std::round(d[a] / period[a]);
  return d;
}

inline Vec3 nearest_image(const World& world, const Vec3& p, const Vec3& near) {
  return near + minimum_image(p - near, periods(world));
}

inline Vec3 wrap_periodic(const World& world, Vec3 p) {
  for (int a = 0; a < 3; ++a)
    if (world.periodic[a]) {
      const double period = world.hi[a] - world.lo[a];
      p[a] -= period * std::floor((p[a] - world.lo[a]) / period);
      if (p[a] >= world.hi[a]) p[a] = world.lo[a];  // round-off of a point just below lo
    }
  return p;
}

}  // namespace talus
