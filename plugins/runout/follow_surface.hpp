// The velocity of a flow that follows the terrain, carried as its plan part
// v (the surface velocity is u = (v, grad Z . v)). Moving from a point with
// gradient G0 to one with gradient G1, u is projected onto the new tangent
// plane and scaled back to `speed` (its magnitude along the surface): the
// terrain's reaction turns the flow but does no work on it. On a smooth
// surface this is, to first order in the step, the centripetal term
// -cos^2(theta) grad Z (v.H.v) of the plan equations of motion; at a sharp
// break it is the redirection the break imposes, without the loss of the
// normal component that keeping v unchanged would cost (cos^2 of the angle
// turned).
#pragma once

#include <cmath>

#include "talus/vec3.hpp"

namespace talus::runout {

inline Vec3 follow_surface(const Vec3& v, const Vec3& g0, const Vec3& g1, double speed) {
  const Vec3 u{v.x, v.y, g0.x * v.x + g0.y * v.y};
  const Vec3 n{-g1.x, -g1.y, 1.0};  // normal at the new point, not normalised
  const Vec3 t = u - (dot(u, n) / norm2(n)) * n;
  const double vt = std::sqrt(norm2(t));
  if (!(vt > 0.0)) return {};
  const double scale = speed / vt;
  return {t.x * scale, t.y * scale, 0.0};
}

}  // namespace talus::runout
