// STL (ASCII and binary) and OBJ readers, and the geometric queries walls and
// fill regions need. Meshes here are small (tanks, beaches, blocks), so the
// queries are brute force over the triangles.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>

#include "talus/error.hpp"
#include "talus/mesh.hpp"

namespace talus {

namespace {

[[noreturn]] void bad(const std::string& path, const std::string& what) {
  throw InputError("error: " + path + ": " + what);
}

std::string extension(const std::string& path) {
  const auto dot = path.find_last_of('.');
  std::string e = dot == std::string::npos ? "" : path.substr(dot + 1);
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return std::tolower(c); });
  return e;
}

// Merges identical vertices so that the mesh is indexed (STL repeats them).
int vertex_index(TriangleMesh& m, const Vec3& p) {
  for (int i = static_cast<int>(m.vertices.size()) - 1; i >= 0 && i >= static_cast<int>(m.vertices.size()) - 64; --i)
    if (m.vertices[i] == p) return i;
  for (int i = 0; i < static_cast<int>(m.vertices.size()); ++i)
    if (m.vertices[i] == p) return i;
  m.vertices.push_back(p);
  return static_cast<int>(m.vertices.size()) - 1;
}

TriangleMesh read_stl(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) bad(path, std::string("cannot open mesh file: ") + std::strerror(errno));
  std::string content((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  TriangleMesh m;
  const bool ascii = content.rfind("solid", 0) == 0 && content.find("facet") != std::string::npos;
  if (ascii) {
    std::istringstream s(content);
    std::string word;
    std::vector<Vec3> corners;
    int line_triangles = 0;
    while (s >> word) {
      if (word == "vertex") {
        Vec3 p;
        if (!(s >> p.x >> p.y >> p.z)) bad(path, "malformed vertex in ASCII STL after facet " + std::to_string(line_triangles));
        corners.push_back(p);
      } else if (word == "endfacet") {
        if (corners.size() != 3) bad(path, "facet " + std::to_string(line_triangles) + " does not have 3 vertices");
        m.triangles.push_back({vertex_index(m, corners[0]), vertex_index(m, corners[1]), vertex_index(m, corners[2])});
        corners.clear();
        ++line_triangles;
      }
    }
  } else {
    if (content.size() < 84) bad(path, "too short to be a binary STL file");
    std::uint32_t count = 0;
    std::memcpy(&count, content.data() + 80, 4);
    if (content.size() < 84 + 50ull * count)
      bad(path, "binary STL declares " + std::to_string(count) + " triangles but the file is truncated");
    for (std::uint32_t t = 0; t < count; ++t) {
      const char* rec = content.data() + 84 + 50ull * t;
      std::array<int, 3> tri{};
      for (int k = 0; k < 3; ++k) {
        float xyz[3];
        std::memcpy(xyz, rec + 12 + 12 * k, 12);
        tri[k] = vertex_index(m, {xyz[0], xyz[1], xyz[2]});
      }
      m.triangles.push_back(tri);
    }
  }
  return m;
}

TriangleMesh read_obj(const std::string& path) {
  std::ifstream in(path);
  if (!in) bad(path, std::string("cannot open mesh file: ") + std::strerror(errno));
  TriangleMesh m;
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    std::istringstream s(line);
    std::string tag;
    if (!(s >> tag)) continue;
    if (tag == "v") {
      Vec3 p;
      if (!(s >> p.x >> p.y >> p.z)) bad(path + ":" + std::to_string(number), "malformed vertex");
      m.vertices.push_back(p);
    } else if (tag == "f") {
      std::vector<int> face;
      std::string item;
      while (s >> item) {
        const int k = std::atoi(item.c_str());  // "7", "7/1" or "7/1/3": the vertex index comes first
        const int n = static_cast<int>(m.vertices.size());
        const int index = k > 0 ? k - 1 : n + k;
        if (k == 0 || index < 0 || index >= n)
          bad(path + ":" + std::to_string(number), "face refers to vertex " + item + " but only " + std::to_string(n) +
                                                       " vertices are defined so far");
        face.push_back(index);
      }
      if (face.size() < 3) bad(path + ":" + std::to_string(number), "a face needs at least 3 vertices");
      for (std::size_t k = 1; k + 1 < face.size(); ++k) m.triangles.push_back({face[0], face[k], face[k + 1]});
    }
  }
  return m;
}

double point_triangle_distance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, Vec3& closest) {
  // Ericson, Real-Time Collision Detection, 5.1.5: closest point by Voronoi regions.
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return norm(p - (closest = a));
  const Vec3 bp = p - b;
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return norm(p - (closest = b));
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return norm(p - (closest = a + ab * (d1 / (d1 - d3))));
  const Vec3 cp = p - c;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return norm(p - (closest = c));
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return norm(p - (closest = a + ac * (d2 / (d2 - d6))));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return norm(p - (closest = b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)))));
  const double denom = 1.0 / (va + vb + vc);
  closest = a + ab * (vb * denom) + ac * (vc * denom);
  return norm(p - closest);
}

}  // namespace

Vec3 TriangleMesh::normal(std::size_t t) const {
  const auto& tri = triangles[t];
  const Vec3 n = cross(vertices[tri[1]] - vertices[tri[0]], vertices[tri[2]] - vertices[tri[0]]);
  const double l = norm(n);
  return l > 0 ? n / l : Vec3{};
}

void TriangleMesh::bounds(Vec3& lo, Vec3& hi) const {
  lo = {1e300, 1e300, 1e300};
  hi = {-1e300, -1e300, -1e300};
  for (const auto& p : vertices)
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], p[a]);
      hi[a] = std::max(hi[a], p[a]);
    }
}

bool TriangleMesh::contains(const Vec3& p) const {
  // Möller–Trumbore ray casting along a direction unlikely to graze edges.
  const Vec3 dir{0.5773, 0.5774, 0.5776};
  int crossings = 0;
  for (const auto& tri : triangles) {
    const Vec3 a = vertices[tri[0]], e1 = vertices[tri[1]] - a, e2 = vertices[tri[2]] - a;
    const Vec3 q = cross(dir, e2);
    const double det = dot(e1, q);
    if (std::abs(det) < 1e-300) continue;
    const double inv = 1.0 / det;
    const Vec3 s = p - a;
    const double u = dot(s, q) * inv;
    if (u < 0 || u > 1) continue;
    const Vec3 r = cross(s, e1);
    const double w = dot(dir, r) * inv;
    if (w < 0 || u + w > 1) continue;
    if (dot(e2, r) * inv > 0) ++crossings;
  }
  return crossings % 2 == 1;
}

double TriangleMesh::distance(const Vec3& p, Vec3* closest) const {
  double best = 1e300;
  for (const auto& tri : triangles) {
    Vec3 c;
    const double d = point_triangle_distance(p, vertices[tri[0]], vertices[tri[1]], vertices[tri[2]], c);
    if (d < best) {
      best = d;
      if (closest) *closest = c;
    }
  }
  return best;
}

std::string TriangleMesh::closure_problem() const {
  // Each edge of a closed, consistently oriented surface is walked once in
  // each direction by the two triangles that share it.
  std::map<std::pair<int, int>, std::size_t> first_use;  // directed edge -> the triangle that walks it
  for (std::size_t t = 0; t < triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const std::pair<int, int> edge{triangles[t][k], triangles[t][(k + 1) % 3]};
      if (const auto [it, fresh] = first_use.emplace(edge, t); !fresh)
        return "triangles " + std::to_string(it->second + 1) + " and " + std::to_string(t + 1) +
               " run along their shared edge in the same direction: one of them is flipped (its normal points "
               "the other way)";
    }
  for (const auto& [edge, t] : first_use)
    if (!first_use.count({edge.second, edge.first}))
      return "the surface is not closed: an edge of triangle " + std::to_string(t + 1) +
             " belongs to no other triangle";
  double six_volume = 0.0;
  for (const auto& tri : triangles)
    six_volume += dot(vertices[tri[0]], cross(vertices[tri[1]], vertices[tri[2]]));
  if (!(six_volume > 0.0))
    return "the triangles are clockwise seen from outside (the normals point inwards, the enclosed volume is "
           "negative): reverse the order of every face's vertices";
  return "";
}

TriangleMesh load_mesh(const std::string& path) {
  const std::string ext = extension(path);
  TriangleMesh m;
  if (ext == "stl")
    m = read_stl(path);
  else if (ext == "obj")
    m = read_obj(path);
  else
    bad(path, "unknown mesh format '." + ext + "'; expected .stl or .obj");
  if (m.triangles.empty()) bad(path, "the mesh has no triangles");
  for (const auto& p : m.vertices)
    if (!is_finite(p)) bad(path, "the mesh has a non-finite vertex coordinate");
  if (const std::string problem = m.closure_problem(); !problem.empty()) bad(path, problem);
  return m;
}

}  // namespace talus
