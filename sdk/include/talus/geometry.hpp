// Shapes in a scene body's "shape" (a one-of object) and the lattices of
// particles that fill them or wall them in. Particles sit on a lattice of
// spacing dp with the first layer half a spacing inside a face, so that fluid
// and wall lattices meet with one spacing across the wall surface. A box
// (and box_walls) whose extent is not a whole number of spacings along an
// axis gets round(L / dp) particles at L / round(L / dp) along it, so that
// its faces lie where the scene says (lattice_adjustment says what changed).
// A box under two spacings along an axis is refused.
//
//   box        { min, max }
//   sphere     { centre, radius }
//   cylinder   { base, axis, radius, height }          (3D)
//   half_space { point, normal }  fills the domain on the side opposite the normal
//   box_walls  { min, max, open: ["+z", ...] }         walls outside the box
//   mesh       { file, scale, offset }                 closed STL/OBJ surface
//   wedge      { origin, length, width, height }       right-angled prism (blocks)
//   tetrahedron{ vertices }                            4 points (blocks)
//   polyhedron { vertices, faces }                     convex, faces CCW from outside (blocks)
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "talus/config.hpp"
#include "talus/params.hpp"
#include "talus/vec3.hpp"

namespace talus {

// Declares the "shape" one-of of a scene body (all alternatives; which ones a
// body kind accepts is checked with the body).
TALUS_API void declare_shape(ParamSet& body);

// Points of a lattice of spacing dp inside the shape (`shape` is the body's
// values, `alternative` the chosen shape). box_walls has no inside: error.
TALUS_API std::vector<Vec3> fill_points(const std::string& alternative, const ParamValues& shape, double dp,
                                        int dim, const Vec3& domain_lo, const Vec3& domain_hi);

// `layers` layers of wall particles just outside the shape's surface (for
// box_walls, outside the box except on open faces; for the others, inside the
// solid shape, so that fluid outside it is walled).
TALUS_API std::vector<Vec3> wall_points(const std::string& alternative, const ParamValues& shape, double dp, int dim,
                                        int layers, const Vec3& domain_lo, const Vec3& domain_hi);

// The point of the wall surface nearest a point in the wall material: for
// box_walls the nearest point of the box (on a face, or an edge or corner
// behind which the point lies), for a solid the nearest point of its
// surface. mDBC mirrors a wall particle x across it to its ghost node
// 2 s - x; a fluid particle found inside a wall is put back there.
TALUS_API std::function<Vec3(const Vec3&)> wall_surface(const std::string& alternative, const ParamValues& shape,
                                                        int dim, const Vec3& domain_lo, const Vec3& domain_hi);

// Whether a point lies in the material of a wall of this shape with `layers`
// layers: for box_walls the slab of the walls outside the closed faces, for a
// solid the solid. A fluid particle there has passed through the wall.
TALUS_API std::function<bool(const Vec3&)> wall_region(const std::string& alternative, const ParamValues& shape,
                                                       double dp, int dim, int layers, const Vec3& domain_lo,
                                                       const Vec3& domain_hi);

// The volume of one particle of the shape's lattice: dp^dim, or the product
// of a box's adjusted spacings.
TALUS_API double lattice_volume(const std::string& alternative, const ParamValues& shape, double dp, int dim);

// What the lattice changes from dp to fit the shape, for the user ("" if nothing).
TALUS_API std::string lattice_adjustment(const std::string& alternative, const ParamValues& shape, double dp,
                                         int dim);

}  // namespace talus
