// Triangle meshes from STL (ASCII or binary) and Wavefront OBJ files, for
// walls, fill regions and block shapes. Errors name the file and the line.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "talus/config.hpp"
#include "talus/vec3.hpp"

namespace talus {

struct TALUS_API TriangleMesh {
  std::vector<Vec3> vertices;
  std::vector<std::array<int, 3>> triangles;  // counter-clockwise seen from outside

  Vec3 normal(std::size_t t) const;  // unit outward normal of triangle t
  void bounds(Vec3& lo, Vec3& hi) const;
  // Inside test for a closed mesh (ray parity along a skewed direction).
  bool contains(const Vec3& p) const;
  // Unsigned distance from p to the surface, with the closest point.
  double distance(const Vec3& p, Vec3* closest = nullptr) const;
  // "" for a closed surface with every triangle counter-clockwise seen from
  // outside; otherwise what is wrong (load_mesh refuses such a mesh).
  std::string closure_problem() const;
};

// Reads .stl or .obj (decided by extension). OBJ polygons are fanned into
// triangles. Throws InputError naming the file on any problem, an open or
// inconsistently oriented surface included.
TALUS_API TriangleMesh load_mesh(const std::string& path);

}  // namespace talus
