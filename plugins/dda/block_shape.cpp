#include "block_shape.hpp"

#include <vector>

#include "talus/mesh.hpp"

namespace talus::dda {

BlockGeometry block_geometry(const ParamValues& body, const std::string& name) {
  const std::string& kind = body.alternative("shape");
  const ParamValues& s = body.alternative_values("shape");
  std::vector<Vec3> v;
  std::vector<std::vector<int>> f;
  if (kind == "box") {
    box_polyhedron(s.vector("min"), s.vector("max"), v, f);
  } else if (kind == "wedge") {
    wedge_polyhedron(s.vector("origin"), s.real("length"), s.real("height"), s.real("width"), v, f);
  } else if (kind == "tetrahedron") {
    const auto corners = s.vectors("vertices");
    if (corners.size() != 4)
      s.fail("vertices", "block '" + name + "': a tetrahedron has 4 vertices, got " + std::to_string(corners.size()));
    tetrahedron_polyhedron(corners, v, f);
  } else if (kind == "polyhedron") {
    v = s.vectors("vertices");
    f = s.index_lists("faces");
  } else if (kind == "mesh") {
    const TriangleMesh mesh = s.read_file("file", [](const std::string& f) { return load_mesh(f); });
    const double scale = s.has("scale") ? s.real("scale") : 1.0;
    const Vec3 offset = s.has("offset") ? s.vector("offset") : Vec3{};
    for (const auto& p : mesh.vertices) v.push_back(p * scale + offset);
    for (const auto& t : mesh.triangles) f.push_back({t[0], t[1], t[2]});
    double size = 0.0;
    detail::bounds_centre(v, &size);
    weld_vertices(v, f, 1e-9 * size);  // STL repeats every corner
    for (std::size_t k = 0; k < f.size(); ++k)
      if (f[k].size() < 3)
        s.fail("file", "block '" + name + "': triangle " + std::to_string(k) + " of the mesh has zero area");
  } else {
    body.fail("shape", "block '" + name + "': a block must be a convex polyhedron (box, wedge, tetrahedron, "
                                          "polyhedron or mesh), not a " + kind);
  }
  BlockGeometry g;
  const std::string problem = make_convex_polyhedron(std::move(v), std::move(f), g.shape, g.props);
  if (!problem.empty()) s.fail("", "block '" + name + "': " + problem);
  return g;
}

}  // namespace talus::dda
