// How many particles a body's shape will hold at spacing dp, from its volume
// or surface, without making them: the resource estimate runs before any
// particle is allocated. Estimates, not counts; they err on the high side.
#pragma once

#include <string>

#include "talus/params.hpp"
#include "talus/vec3.hpp"

namespace talus {

// Particles fill_points would make (talus/geometry.hpp).
double fill_count_estimate(const std::string& alternative, const ParamValues& shape, double dp, int dim,
                           const Vec3& domain_lo, const Vec3& domain_hi);

// Particles wall_points would make: a layer of thickness `thickness` along the surface.
double wall_count_estimate(const std::string& alternative, const ParamValues& shape, double dp, int dim,
                           double thickness, const Vec3& domain_lo, const Vec3& domain_hi);

// Surface area of a block's shape (of its bounding box where that is
// simpler; perimeter in 2D), for the particles a block carries under its faces.
double bounding_surface(const std::string& alternative, const ParamValues& shape, int dim);

}  // namespace talus
