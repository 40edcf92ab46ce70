#include "shape_estimate.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "shape_mesh.hpp"
#include "talus/mesh.hpp"

namespace talus {

namespace {

constexpr double pi = std::numbers::pi;

struct Box {
  Vec3 lo, hi;
};

// Lattice points along each axis of [lo, hi], as the lattice makes them.
double lattice_count(const Vec3& lo, const Vec3& hi, double dp, int dim) {
  double n = 1.0;
  for (int a = 0; a < dim; ++a) n *= std::max(0.0, std::round((hi[a] - lo[a]) / dp));
  return n;
}

double extent_volume(const Box& b, int dim) {
  double v = 1.0;
  for (int a = 0; a < dim; ++a) v *= std::max(0.0, b.hi[a] - b.lo[a]);
  return v;
}

double extent_surface(const Box& b, int dim) {
  const Vec3 e = b.hi - b.lo;
  if (dim == 2) return 2.0 * (std::abs(e.x) + std::abs(e.y));
  return 2.0 * (std::abs(e.x * e.y) + std::abs(e.y * e.z) + std::abs(e.z * e.x));
}

Box bounds_of(const std::vector<Vec3>& points) {
  Box b{points.empty() ? Vec3{} : points.front(), points.empty() ? Vec3{} : points.front()};
  for (const Vec3& p : points)
    for (int a = 0; a < 3; ++a) {
      b.lo[a] = std::min(b.lo[a], p[a]);
      b.hi[a] = std::max(b.hi[a], p[a]);
    }
  return b;
}

struct MeshMeasure {
  Box box;
  double volume = 0.0, area = 0.0;
};

MeshMeasure measure_mesh(const ParamValues& v) {
  const TriangleMesh m = scaled_mesh(v);
  MeshMeasure r;
  m.bounds(r.box.lo, r.box.hi);
  for (const auto& t : m.triangles) {
    const Vec3 a = m.vertices[t[0]], b = m.vertices[t[1]], c = m.vertices[t[2]];
    r.area += 0.5 * norm(cross(b - a, c - a));
    r.volume += dot(a, cross(b, c)) / 6.0;
  }
  r.volume = std::abs(r.volume);
  return r;
}

// Area (length in 2D) of the plane through x0 with normal n inside the box:
// at most the box's face across the normal's largest component, divided by it.
double plane_section(const Vec3& n_raw, const Box& domain, int dim) {
  const double len = norm(n_raw);
  if (!(len > 0.0)) return 0.0;
  const Vec3 n = n_raw / len;
  int major = 0;
  for (int a = 1; a < dim; ++a)
    if (std::abs(n[a]) > std::abs(n[major])) major = a;
  double face = 1.0;
  for (int a = 0; a < dim; ++a)
    if (a != major) face *= domain.hi[a] - domain.lo[a];
  return face / std::abs(n[major]);
}

double ball_volume(double r, int dim) { return dim == 3 ? 4.0 / 3.0 * pi * r * r * r : pi * r * r; }

}  // namespace

double fill_count_estimate(const std::string& alt, const ParamValues& v, double dp, int dim, const Vec3& dlo,
                           const Vec3& dhi) {
  const double cell = std::pow(dp, dim);
  if (alt == "box") return lattice_count(v.vector("min"), v.vector("max"), dp, dim);
  if (alt == "sphere") return ball_volume(v.real("radius"), dim) / cell;
  if (alt == "cylinder") return pi * v.real("radius") * v.real("radius") * v.real("height") / cell;
  if (alt == "polygon") {
    const auto c = v.vectors("vertices");
    double twice = 0.0;
    for (std::size_t k = 0; k < c.size(); ++k) {
      const Vec3& a = c[k];
      const Vec3& b = c[(k + 1) % c.size()];
      twice += a.x * b.y - b.x * a.y;
    }
    return 0.5 * std::abs(twice) / cell;
  }
  if (alt == "half_space") {
    // The share of the domain (the body is clipped to it) behind the plane,
    // counted on a coarse grid.
    const Vec3 x0 = v.vector("point"), n = v.vector("normal");
    const Vec3 dlo_ = dlo, dhi_ = dhi;
    constexpr int k = 64;
    double behind = 0.0, total = 0.0;
    for (int i = 0; i < k; ++i)
      for (int j = 0; j < k; ++j)
        for (int l = 0; l < (dim == 3 ? k : 1); ++l) {
          const Vec3 f{(i + 0.5) / k, (j + 0.5) / k, dim == 3 ? (l + 0.5) / k : 0.0};
          const Vec3 p{dlo_.x + f.x * (dhi_.x - dlo_.x), dlo_.y + f.y * (dhi_.y - dlo_.y), dlo_.z + f.z * (dhi_.z - dlo_.z)};
          behind += dot(p - x0, n) < 0.0;
          total += 1.0;
        }
    return extent_volume({dlo_, dhi_}, dim) * (behind / total) / cell;
  }
  if (alt == "mesh") {
    // In 2D the lattice is the mesh's section by z = 0: its bounding box in
    // plan bounds it (the mesh's volume does not: a thin slab holds little).
    const MeshMeasure m = measure_mesh(v);
    return (dim == 2 ? extent_volume(m.box, 2) : std::min(m.volume, extent_volume(m.box, 3))) / cell;
  }
  return 0.0;  // not a fillable shape: the build reports it
}

double wall_count_estimate(const std::string& alt, const ParamValues& v, double dp, int dim, double t,
                           const Vec3& dlo, const Vec3& dhi) {
  const double cell = std::pow(dp, dim);
  if (alt == "box_walls") {
    const Vec3 lo = v.vector("min"), hi = v.vector("max");
    const auto& open = v.strings("open");
    auto closed = [&](const std::string& face) { return std::find(open.begin(), open.end(), face) == open.end(); };
    Vec3 olo = lo, ohi = hi;
    for (int a = 0; a < dim; ++a) {
      const std::string axis(1, static_cast<char>('x' + a));
      if (closed("-" + axis)) olo[a] -= t;
      if (closed("+" + axis)) ohi[a] += t;
    }
    return std::max(0.0, lattice_count(olo, ohi, dp, dim) - lattice_count(lo, hi, dp, dim));
  }
  if (alt == "box") {
    Box inner{v.vector("min"), v.vector("max")};
    const double whole = extent_volume(inner, dim);
    for (int a = 0; a < dim; ++a) {
      inner.lo[a] += t;
      inner.hi[a] -= t;
    }
    return (whole - extent_volume(inner, dim)) / cell;
  }
  if (alt == "sphere") {
    const double r = v.real("radius");
    return (ball_volume(r, dim) - ball_volume(std::max(0.0, r - t), dim)) / cell;
  }
  if (alt == "cylinder") {
    const double r = v.real("radius"), h = v.real("height"), ri = std::max(0.0, r - t);
    return (pi * r * r * h - pi * ri * ri * std::max(0.0, h - 2.0 * t)) / cell;
  }
  if (alt == "polygon") {
    const auto c = v.vectors("vertices");
    double perimeter = 0.0;
    for (std::size_t k = 0; k < c.size(); ++k) perimeter += norm(c[(k + 1) % c.size()] - c[k]);
    return std::min(fill_count_estimate(alt, v, dp, dim, dlo, dhi), perimeter * t / cell);
  }
  if (alt == "half_space") return plane_section(v.vector("normal"), {dlo, dhi}, dim) * t / cell;
  if (alt == "mesh") {
    const MeshMeasure m = measure_mesh(v);
    return (dim == 2 ? extent_volume(m.box, 2) : std::min(extent_volume(m.box, 3), m.area * t)) / cell;
  }
  return 0.0;
}

double bounding_surface(const std::string& alt, const ParamValues& v, int dim) {
  if (alt == "box") return extent_surface({v.vector("min"), v.vector("max")}, dim);
  if (alt == "sphere") {
    const double r = v.real("radius");
    return extent_surface({Vec3{-r, -r, -r}, Vec3{r, r, r}}, dim);
  }
  if (alt == "cylinder") {
    const double e = v.real("radius") + v.real("height");
    return extent_surface({Vec3{-e, -e, -e}, Vec3{e, e, e}}, dim);
  }
  if (alt == "wedge") {
    const double l = v.real("length"), w = v.real("width"), h = v.real("height");
    return l * h + (l + h + std::hypot(l, h)) * w;
  }
  if (alt == "polyhedron" || alt == "tetrahedron") {
    const auto p = v.vectors("vertices");
    if (dim == 2 || p.size() < 4) return extent_surface(bounds_of(p), dim);
    // Tetrahedron: its four faces; polyhedron: each face fanned into triangles.
    const std::vector<std::vector<int>> faces =
        alt == "polyhedron" ? v.index_lists("faces") : std::vector<std::vector<int>>{{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}};
    double area = 0.0;
    for (const auto& f : faces)
      for (std::size_t k = 2; k < f.size(); ++k)
        if (std::max({f[0], f[k - 1], f[k]}) < static_cast<int>(p.size()) && std::min({f[0], f[k - 1], f[k]}) >= 0)
          area += 0.5 * norm(cross(p[f[k - 1]] - p[f[0]], p[f[k]] - p[f[0]]));
    return area;
  }
  if (alt == "polygon") return extent_surface(bounds_of(v.vectors("vertices")), dim);
  if (alt == "mesh") return measure_mesh(v).area;
  return 0.0;
}

}  // namespace talus
