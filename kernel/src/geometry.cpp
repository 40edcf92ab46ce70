// Lattice filling of the scene shapes (fluid bodies) and wall layers (wall
// bodies). Lattices are anchored dp/2 inside a box face so that fluid and
// wall particles meet with spacing dp across the surface.
#include "talus/geometry.hpp"

#include <algorithm>
#include <cmath>
#include <functional>

#include "shape_mesh.hpp"
#include "talus/error.hpp"
#include "talus/mesh.hpp"

namespace talus {

TriangleMesh scaled_mesh(const ParamValues& v) {
  TriangleMesh m = v.read_file("file", [](const std::string& f) { return load_mesh(f); });
  const double s = v.real("scale");
  const Vec3 o = v.vector("offset");
  for (auto& p : m.vertices) p = p * s + o;
  return m;
}

namespace {

// A box's corners: max above min along x and y, not below it along z (a 2D box has no z extent).
void max_above_min(const ParamValues& v, Diagnostics& d) {
  const Vec3 lo = v.vector("min"), hi = v.vector("max");
  for (int a = 0; a < 3; ++a)
    if (!(hi[a] >= lo[a]) || (a < 2 && hi[a] == lo[a])) {
      d.error(v, "max", "must be greater than min in every component");
      break;
    }
}

}  // namespace

void declare_shape(ParamSet& body) {
  auto b = body.one_of("shape").doc("the region the body occupies (a fluid body's must lie in the domain)");

  ParamSet box{"box", "axis-aligned box"};
  box.vector("min").unit("m").doc("lower corner");
  box.vector("max").unit("m").doc("upper corner");
  box.check(max_above_min);
  b.alternative("box", box);

  ParamSet sphere{"sphere", "sphere (a disc in 2D)"};
  sphere.vector("centre").unit("m").doc("centre");
  sphere.real("radius").unit("m").greater_than(0.0).doc("radius");
  b.alternative("sphere", sphere);

  ParamSet cylinder{"cylinder", "circular cylinder (3D)"};
  cylinder.vector("base").unit("m").doc("centre of the base disc");
  cylinder.vector("axis").default_value({0.0, 0.0, 1.0}, {0.0, 1.0}).doc("direction of the axis");
  cylinder.real("radius").unit("m").greater_than(0.0).doc("radius");
  cylinder.real("height").unit("m").greater_than(0.0).doc("length along the axis");
  b.alternative("cylinder", cylinder);

  ParamSet polygon{"polygon", "simple polygon in the x-y plane (2D domains: a release area, a plan-view region)"};
  polygon.vector_list("vertices").unit("m").doc("corners in order (either sense); the last joins the first");
  polygon.check([](const ParamValues& v, Diagnostics& d) {
    const auto pts = v.vectors("vertices");
    if (pts.size() < 3) d.error(v, "vertices", "a polygon needs at least 3 corners, got " + std::to_string(pts.size()));
  });
  b.alternative("polygon", polygon);

  ParamSet half{"half_space", "everything in the domain behind a plane"};
  half.vector("point").unit("m").doc("a point on the plane");
  half.vector("normal").doc("outward normal: the body is on the side opposite to it");
  b.alternative("half_space", half);

  ParamSet walls{"box_walls", "the walls of a box-shaped tank, outside the box, some faces open"};
  walls.vector("min").unit("m").doc("inner lower corner");
  walls.vector("max").unit("m").doc("inner upper corner");
  walls.string_list("open", {"-x", "+x", "-y", "+y", "-z", "+z"}).optional().doc("faces without a wall (default none)");
  walls.check(max_above_min);
  b.alternative("box_walls", walls);

  ParamSet mesh{"mesh", "closed triangle mesh from an STL or OBJ file"};
  mesh.path("file").doc("the .stl or .obj file, relative to the scene");
  mesh.real("scale").default_value(1.0).greater_than(0.0).doc("factor applied to the coordinates");
  mesh.vector("offset").unit("m").default_value({0.0, 0.0, 0.0}, {0.0, 0.0}).doc("translation applied after scaling");
  b.alternative("mesh", mesh);

  ParamSet wedge{"wedge", "right-angled triangular prism: the triangle (0,0),(length,0),(0,height) in x-z, extruded along y"};
  wedge.vector("origin").unit("m").length(3).doc("corner at the right angle, lowest y");
  wedge.real("length").unit("m").greater_than(0.0).doc("leg along x");
  wedge.real("height").unit("m").greater_than(0.0).doc("leg along z");
  wedge.real("width").unit("m").greater_than(0.0).doc("extrusion along y");
  b.alternative("wedge", wedge);

  ParamSet tetra{"tetrahedron", "tetrahedron from four points"};
  tetra.vector_list("vertices").unit("m").doc("the four corners");
  b.alternative("tetrahedron", tetra);

  ParamSet poly{"polyhedron", "convex polyhedron"};
  poly.vector_list("vertices").unit("m").doc("corner points");
  poly.index_lists("faces").doc("each face as vertex indices, counter-clockwise seen from outside");
  b.alternative("polyhedron", poly);
}

namespace {

// A lattice point is kept, or dropped together with the next `skip` points
// along +x: those lie closer to it than its distance to anything kept.
struct Verdict {
  bool keep = false;
  long long skip = 0;
};
using Classify = std::function<Verdict(const Vec3&)>;

// Lattice points after a dropped one along x that certainly lie within
// `distance` of it (one fewer than fit, for rounding in the distance).
long long points_within(double distance, double dp) {
  const double n = std::floor(distance / dp) - 1.0;
  if (!(n > 0.0)) return 0;
  return n < 1e18 ? static_cast<long long>(n) : 1'000'000'000'000'000'000LL;
}

// Lattice points p = lo + (i + 1/2) dp within [lo, hi] that classify keeps.
// Skipping makes the work grow with the points kept and the rows, not with
// the volume of [lo, hi]: a wall around a large tank costs its surface.
std::vector<Vec3> lattice(const Vec3& lo, const Vec3& hi, double dp, int dim, const Classify& classify) {
  long long n[3] = {1, 1, 1};
  for (int a = 0; a < dim; ++a) n[a] = std::max(0LL, std::llround((hi[a] - lo[a]) / dp));
  std::vector<Vec3> out;
  for (long long k = 0; k < n[2]; ++k)
    for (long long j = 0; j < n[1]; ++j)
      for (long long i = 0; i < n[0]; ++i) {
        const Vec3 p{lo.x + (i + 0.5) * dp, lo.y + (j + 0.5) * dp, dim == 3 ? lo.z + (k + 0.5) * dp : 0.0};
        const Verdict v = classify(p);
        if (v.keep)
          out.push_back(p);
        else
          i += std::min(v.skip, n[0]);
      }
  return out;
}

// Indices i of the lattice points origin + (i + 1/2) dp, 0 <= i < n, that lie in [lo, hi]: first <= i < end.
struct IndexRange {
  long long first = 0, end = 1;
  bool contains(long long i) const { return i >= first && i < end; }
};

IndexRange inside_indices(double origin, double lo, double hi, double dp, long long n) {
  auto at = [&](long long i) { return origin + (i + 0.5) * dp; };
  const double nd = static_cast<double>(n);
  long long first = static_cast<long long>(std::clamp(std::ceil((lo - origin) / dp - 0.5), 0.0, nd));
  // From the estimate, moved by the points' own arithmetic so that the range matches p < lo and p > hi exactly.
  while (first > 0 && at(first - 1) >= lo) --first;
  while (first < n && at(first) < lo) ++first;
  long long end = static_cast<long long>(std::clamp(std::floor((hi - origin) / dp - 0.5) + 1.0, 0.0, nd));
  end = std::max(end, first);
  while (end > first && at(end - 1) > hi) --end;
  while (end < n && at(end) <= hi) ++end;
  return {first, end};
}

// The lattice over [olo, ohi] less the points in the inner box [lo, hi]
// (the walls of a tank), in lattice order. Rows and planes inside the box
// are passed over by index, so a tall tank with open sides costs its walls.
std::vector<Vec3> box_wall_lattice(const Vec3& olo, const Vec3& ohi, const Vec3& lo, const Vec3& hi, double dp, int dim) {
  long long n[3] = {1, 1, 1};
  IndexRange inside[3];
  for (int a = 0; a < dim; ++a) {
    n[a] = std::max(0LL, std::llround((ohi[a] - olo[a]) / dp));
    inside[a] = inside_indices(olo[a], lo[a], hi[a], dp, n[a]);
  }
  const bool rows_all_inside = inside[0].first == 0 && inside[0].end == n[0];
  const bool planes_all_inside = rows_all_inside && inside[1].first == 0 && inside[1].end == n[1];
  std::vector<Vec3> out;
  for (long long k = 0; k < n[2]; ++k) {
    const bool z_inside = inside[2].contains(k);
    if (z_inside && planes_all_inside) {  // no wall crosses this plane, nor the planes up to the box's far face
      k = inside[2].end - 1;
      continue;
    }
    for (long long j = 0; j < n[1]; ++j) {
      const bool row_inside = z_inside && inside[1].contains(j);
      if (row_inside && rows_all_inside) {
        j = inside[1].end - 1;
        continue;
      }
      const double y = olo.y + (j + 0.5) * dp, z = dim == 3 ? olo.z + (k + 0.5) * dp : 0.0;
      for (long long i = 0; i < n[0]; ++i) {
        if (row_inside && inside[0].contains(i)) i = inside[0].end;
        if (i < n[0]) out.push_back({olo.x + (i + 0.5) * dp, y, z});
      }
    }
  }
  return out;
}

// A solid shape: its bounding box, inside(p), and the distance from p to its
// surface (exact, on either side: the lattice skips by it).
struct Solid {
  Vec3 lo, hi;
  std::function<bool(const Vec3&)> inside;
  std::function<double(const Vec3&)> distance;
};

Solid solid(const std::string& alt, const ParamValues& v, int dim, const Vec3& dlo, const Vec3& dhi) {
  if (alt == "box") {
    const Vec3 lo = v.vector("min"), hi = v.vector("max");
    return {lo, hi,
            [=](const Vec3& p) {
              for (int a = 0; a < dim; ++a)
                if (p[a] < lo[a] || p[a] > hi[a]) return false;
              return true;
            },
            [=](const Vec3& p) {
              double depth = 1e300, outside = 0.0;
              for (int a = 0; a < dim; ++a) {
                depth = std::min({depth, p[a] - lo[a], hi[a] - p[a]});
                const double beyond = std::max({0.0, lo[a] - p[a], p[a] - hi[a]});
                outside += beyond * beyond;
              }
              return outside > 0.0 ? std::sqrt(outside) : depth;
            }};
  }
  if (alt == "sphere") {
    const Vec3 c = v.vector("centre");
    const double r = v.real("radius");
    const Vec3 e{r, r, dim == 3 ? r : 0.0};
    return {c - e, c + e, [=](const Vec3& p) { return norm(p - c) < r; }, [=](const Vec3& p) { return std::abs(r - norm(p - c)); }};
  }
  if (alt == "cylinder") {
    if (dim != 3) v.fail("", "a cylinder needs a 3D domain (use a box in 2D)");
    const Vec3 base = v.vector("base");
    Vec3 axis = v.vector("axis");
    if (!(norm(axis) > 0.0)) v.fail("axis", "must not be the zero vector");
    axis = axis / norm(axis);
    const double r = v.real("radius"), len = v.real("height");
    const double ext = r + len;
    const Vec3 e{ext, ext, ext};
    auto radial = [=](const Vec3& p) { const Vec3 d = p - base; return norm(d - axis * dot(d, axis)); };
    return {base - e, base + e,
            [=](const Vec3& p) { const double s = dot(p - base, axis); return s >= 0 && s <= len && radial(p) < r; },
            [=](const Vec3& p) {
              const double s = dot(p - base, axis), rho = radial(p);
              const double axial = std::max(-s, s - len), across = rho - r;
              if (axial <= 0.0 && across <= 0.0) return std::min(-axial, -across);
              return std::hypot(std::max(0.0, axial), std::max(0.0, across));
            }};
  }
  if (alt == "polygon") {
    if (dim != 2) v.fail("", "a polygon is a plan-view shape for 2D domains (use a mesh or polyhedron in 3D)");
    const std::vector<Vec3> c = v.vectors("vertices");
    Vec3 lo = c[0], hi = c[0];
    double twice_area = 0.0;
    for (std::size_t k = 0; k < c.size(); ++k) {
      const Vec3& a = c[k];
      const Vec3& b = c[(k + 1) % c.size()];
      twice_area += a.x * b.y - b.x * a.y;
      for (int ax = 0; ax < 2; ++ax) {
        lo[ax] = std::min(lo[ax], a[ax]);
        hi[ax] = std::max(hi[ax], a[ax]);
      }
    }
    if (!(std::abs(twice_area) > 0.0)) v.fail("vertices", "the polygon has no area (collinear corners)");
    // Even-odd rule: a horizontal ray from p crosses the boundary an odd number of times.
    auto inside = [c](const Vec3& p) {
      bool in = false;
      for (std::size_t k = 0, m = c.size() - 1; k < c.size(); m = k++)
        if ((c[k].y > p.y) != (c[m].y > p.y) &&
            p.x < c[m].x + (p.y - c[m].y) * (c[k].x - c[m].x) / (c[k].y - c[m].y))
          in = !in;
      return in;
    };
    auto edge_distance = [c](const Vec3& p) {
      double d = 1e300;
      for (std::size_t k = 0; k < c.size(); ++k) {
        const Vec3 a = c[k], e = c[(k + 1) % c.size()] - a;
        const double t = std::clamp(dot(p - a, e) / dot(e, e), 0.0, 1.0);
        d = std::min(d, norm(p - (a + e * t)));
      }
      return d;
    };
    return {lo, hi, inside, edge_distance};
  }
  if (alt == "half_space") {
    const Vec3 x0 = v.vector("point");
    Vec3 n = v.vector("normal");
    if (!(norm(n) > 0.0)) v.fail("normal", "must not be the zero vector");
    n = n / norm(n);
    return {dlo, dhi, [=](const Vec3& p) { return dot(p - x0, n) < 0.0; }, [=](const Vec3& p) { return std::abs(dot(p - x0, n)); }};
  }
  if (alt == "mesh") {
    auto mesh = std::make_shared<TriangleMesh>(scaled_mesh(v));
    Vec3 lo, hi;
    mesh->bounds(lo, hi);
    return {lo, hi, [mesh](const Vec3& p) { return mesh->contains(p); },
            [mesh](const Vec3& p) { return mesh->distance(p); }};
  }
  v.fail("", "shape '" + alt + "' cannot be filled with particles (it is for blocks or walls only)");
}

}  // namespace

std::vector<Vec3> fill_points(const std::string& alt, const ParamValues& v, double dp, int dim, const Vec3& dlo,
                              const Vec3& dhi) {
  if (alt == "box_walls") v.fail("", "box_walls has no inside to fill; use box for a fluid body");
  const Solid s = solid(alt, v, dim, dlo, dhi);
  if (alt == "box") return lattice(s.lo, s.hi, dp, dim, [](const Vec3&) { return Verdict{true}; });
  // A half-space is what lies in the domain behind its plane; its lattice box
  // (the domain, as for any bounding box) reaches dp/2 beyond the domain.
  const bool clip_to_domain = alt == "half_space";
  auto beyond_domain = [&](const Vec3& p) {
    if (!clip_to_domain) return false;
    for (int a = 0; a < dim; ++a)
      if (p[a] < dlo[a] || p[a] > dhi[a]) return true;
    return false;
  };
  // Anchor at the bounding box so the lattice is the same as for a box.
  return lattice(s.lo, s.hi + Vec3{dp, dp, dp}, dp, dim, [&](const Vec3& p) {
    if (beyond_domain(p)) return Verdict{false};  // no skip: the points after it may be back in the domain
    return s.inside(p) ? Verdict{true} : Verdict{false, points_within(s.distance(p), dp)};
  });
}

std::vector<Vec3> wall_points(const std::string& alt, const ParamValues& v, double dp, int dim, int layers,
                              const Vec3& dlo, const Vec3& dhi) {
  const double thickness = layers * dp;
  if (alt == "box_walls") {
    const Vec3 lo = v.vector("min"), hi = v.vector("max");
    const auto& open = v.strings("open");
    auto is_open = [&](const char* face) { return std::find(open.begin(), open.end(), face) != open.end(); };
    const char* minus[3] = {"-x", "-y", "-z"};
    const char* plus[3] = {"+x", "+y", "+z"};
    Vec3 olo = lo, ohi = hi;
    for (int a = 0; a < dim; ++a) {
      if (!is_open(minus[a])) olo[a] -= thickness;
      if (!is_open(plus[a])) ohi[a] += thickness;
    }
    return box_wall_lattice(olo, ohi, lo, hi, dp, dim);
  }
  // Kept: inside the solid, less than `thickness` from its surface.
  const Solid s = solid(alt, v, dim, dlo, dhi);
  const Vec3 hi = alt == "box" ? s.hi : s.hi + Vec3{dp, dp, dp};
  return lattice(s.lo, hi, dp, dim, [&](const Vec3& p) {
    const double d = s.distance(p);
    if (!s.inside(p)) return Verdict{false, points_within(d, dp)};
    return d < thickness ? Verdict{true} : Verdict{false, points_within(d - thickness, dp)};
  });
}

}  // namespace talus
