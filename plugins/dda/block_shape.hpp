// A block body's "shape" (box, wedge, tetrahedron, polyhedron, mesh) as a
// validated convex polyhedron with its exact mass properties. Invalid
// geometry is an InputError at the shape's JSON pointer naming the block.
#pragma once

#include <string>

#include "talus/blocks.hpp"
#include "talus/dda/polyhedron.hpp"
#include "talus/params.hpp"

namespace talus::dda {

struct BlockGeometry {
  Polyhedron shape;       // body frame, centroid at the origin
  MassProperties props;   // centroid in the world frame, inertia per unit density
};

// `body` is the block body's scene entry (it has "shape"), `name` its name.
BlockGeometry block_geometry(const ParamValues& body, const std::string& name);

}  // namespace talus::dda
