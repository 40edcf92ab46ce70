// Lattice filling of the scene shapes (fluid bodies) and wall layers (wall
// bodies). Lattices are anchored dp/2 inside a box face so that fluid and
// wall particles meet with spacing dp across the surface.
#include "talus/geometry.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
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

  ParamSet box{"box",
               "axis-aligned box, filled with round(L/dp) particles per axis half a spacing inside its faces (where "
               "L is not a whole number of spacings the spacing along that axis becomes L/round(L/dp), and the "
               "run says so); at least two spacings along every axis"};
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

  ParamSet walls{"box_walls",
                 "the walls of a box-shaped tank, outside the box, some faces open: the box's lattice (as for a box) "
                 "continued across its closed faces, so the walls lie on the faces whichever are open"};
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

// A length for a message: 6 significant digits (0.461 - 0.3 reads 0.161).
std::string digits(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", x);
  return text;
}

// round(L / dp) as a count, within what a long long and the resource check allow.
long long spacings_in(double length, double dp) {
  const double n = std::round(length / dp);
  return n > 0.0 ? static_cast<long long>(std::min(n, 1e15)) : 0;
}

// Lattice points p = lo + (i + 1/2) s within [lo, hi] that classify keeps,
// s the spacing per axis. Skipping makes the work grow with the points kept
// and the rows, not with the volume of [lo, hi]: a wall around a large tank
// costs its surface.
std::vector<Vec3> lattice(const Vec3& lo, const Vec3& hi, const Vec3& s, int dim, const Classify& classify) {
  long long n[3] = {1, 1, 1};
  for (int a = 0; a < dim; ++a) n[a] = spacings_in(hi[a] - lo[a], s[a]);
  std::vector<Vec3> out;
  for (long long k = 0; k < n[2]; ++k)
    for (long long j = 0; j < n[1]; ++j)
      for (long long i = 0; i < n[0]; ++i) {
        const Vec3 p{lo.x + (i + 0.5) * s.x, lo.y + (j + 0.5) * s.y, dim == 3 ? lo.z + (k + 0.5) * s.z : 0.0};
        const Verdict v = classify(p);
        if (v.keep)
          out.push_back(p);
        else
          i += std::min(v.skip, n[0]);
      }
  return out;
}

// A box's lattice: round(L / dp) particles per axis at spacing L / count, the
// first and last layers half a spacing inside the faces (dp itself where L is
// a whole number of spacings, to round-off). Refuses a box under two spacings
// along an axis unless it is exactly one (a column of a staircase): a single
// particle could not keep both faces without a spacing far from dp.
struct BoxLattice {
  long long n[3] = {1, 1, 1};
  Vec3 spacing, origin;  // points origin + (i + 1/2) spacing, 0 <= i < n, per axis
  bool open_end[3] = {false, false, false};  // box_walls: the open face lies off the box's, within dp/2
};

BoxLattice box_lattice(const ParamValues& v, double dp, int dim) {
  const Vec3 lo = v.vector("min"), hi = v.vector("max");
  BoxLattice b;
  b.spacing = {dp, dp, dp};
  b.origin = lo;
  for (int a = 0; a < dim; ++a) {
    const double length = hi[a] - lo[a];
    b.n[a] = spacings_in(length, dp);
    const bool whole = std::abs(length / dp - static_cast<double>(b.n[a])) <= 1e-9 * static_cast<double>(b.n[a]);
    if (length < 2.0 * dp && !whole)
      v.fail("max", "the box spans " + digits(length) + " m along " + std::string(1, static_cast<char>('x' + a)) +
                        ", less than two particle spacings (2 x " + digits(dp) +
                        " m) and not exactly one: make it one spacing, at least two, or refine dp");
    if (!whole) b.spacing[a] = length / static_cast<double>(b.n[a]);
  }
  return b;
}

bool face_closed(const ParamValues& v, int axis, char side) {
  const auto& open = v.strings("open");
  const std::string face{side, static_cast<char>('x' + axis)};
  return std::find(open.begin(), open.end(), face) == open.end();
}

// The lattice of a tank (box_walls): the box's, except along an axis with one
// face open, where the spacing stays dp from the closed face and the open end
// falls within dp/2 of the stated one (the walls' length there is not a face).
BoxLattice tank_lattice(const ParamValues& v, double dp, int dim) {
  BoxLattice b = box_lattice(v, dp, dim);
  const Vec3 hi = v.vector("max");
  for (int a = 0; a < dim; ++a) {
    const bool minus = face_closed(v, a, '-'), plus = face_closed(v, a, '+');
    if (minus == plus || b.spacing[a] == dp) continue;
    b.spacing[a] = dp;
    b.open_end[a] = true;
    if (plus) b.origin[a] = hi[a] - static_cast<double>(b.n[a]) * dp;
  }
  return b;
}

// The walls of a tank: `layers` layers outside each closed face of the box,
// continuing the tank's lattice across the faces, in lattice order. Rows and
// planes inside the box are passed over by index, so a tall tank with open
// sides costs its walls.
std::vector<Vec3> box_wall_lattice(const ParamValues& v, const BoxLattice& box, int layers, int dim) {
  const Vec3& s = box.spacing;
  Vec3 origin = box.origin;
  long long n[3] = {1, 1, 1}, first[3] = {0, 0, 0}, end[3] = {1, 1, 1};  // box: first <= i < end
  for (int a = 0; a < dim; ++a) {
    const long long below = face_closed(v, a, '-') ? layers : 0, above = face_closed(v, a, '+') ? layers : 0;
    origin[a] = box.origin[a] - static_cast<double>(below) * s[a];
    first[a] = below;
    end[a] = below + box.n[a];
    n[a] = end[a] + above;
  }
  auto inside = [&](int a, long long i) { return i >= first[a] && i < end[a]; };
  const bool rows_all_inside = first[0] == 0 && end[0] == n[0];
  const bool planes_all_inside = rows_all_inside && first[1] == 0 && end[1] == n[1];
  std::vector<Vec3> out;
  for (long long k = 0; k < n[2]; ++k) {
    const bool z_inside = inside(2, k);
    if (z_inside && planes_all_inside) {  // no wall crosses this plane, nor the planes up to the box's far face
      k = end[2] - 1;
      continue;
    }
    for (long long j = 0; j < n[1]; ++j) {
      const bool row_inside = z_inside && inside(1, j);
      if (row_inside && rows_all_inside) {
        j = end[1] - 1;
        continue;
      }
      const double y = origin.y + (j + 0.5) * s.y, z = dim == 3 ? origin.z + (k + 0.5) * s.z : 0.0;
      for (long long i = 0; i < n[0]; ++i) {
        if (row_inside && inside(0, i)) i = end[0];
        if (i < n[0]) out.push_back({origin.x + (i + 0.5) * s.x, y, z});
      }
    }
  }
  return out;
}

// A solid shape: its bounding box, inside(p), the distance from p to its
// surface (exact, on either side: the lattice skips by it) and the point of
// the surface nearest a point inside.
struct Solid {
  Vec3 lo, hi;
  std::function<bool(const Vec3&)> inside;
  std::function<double(const Vec3&)> distance;
  std::function<Vec3(const Vec3&)> surface;
};

// The point on the faces of the box [lo, hi] nearest p inside it: p moved
// onto its nearest face, or onto the edge or corner of the faces it is
// equally near (to round-off), so that mirror images stay symmetric.
Vec3 nearest_box_face(const Vec3& p, const Vec3& lo, const Vec3& hi, int dim) {
  double depth = 1e300;
  for (int a = 0; a < dim; ++a) depth = std::min({depth, p[a] - lo[a], hi[a] - p[a]});
  const double tie = depth + 1e-12 * (hi - lo).x;
  Vec3 s = p;
  for (int a = 0; a < dim; ++a) {
    if (p[a] - lo[a] <= tie)
      s[a] = lo[a];
    else if (hi[a] - p[a] <= tie)
      s[a] = hi[a];
  }
  return s;
}

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
            },
            [=](const Vec3& p) { return nearest_box_face(p, lo, hi, dim); }};
  }
  if (alt == "sphere") {
    const Vec3 c = v.vector("centre");
    const double r = v.real("radius");
    const Vec3 e{r, r, dim == 3 ? r : 0.0};
    return {c - e, c + e, [=](const Vec3& p) { return norm(p - c) < r; },
            [=](const Vec3& p) { return std::abs(r - norm(p - c)); },
            [=](const Vec3& p) {
              const double d = norm(p - c);
              return d > 0.0 ? c + (p - c) * (r / d) : c + Vec3{r, 0.0, 0.0};
            }};
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
            },
            [=](const Vec3& p) {
              const Vec3 d = p - base;
              const double s = dot(d, axis);
              const Vec3 out = d - axis * s;
              const double rho = norm(out);
              if (r - rho < std::min(s, len - s))  // the mantle is nearest
                return base + axis * s + (rho > 0.0 ? out * (r / rho) : Vec3{});
              return p + axis * (s < len - s ? -s : len - s);
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
    auto nearest_edge_point = [c](const Vec3& p) {
      double d = 1e300;
      Vec3 nearest;
      for (std::size_t k = 0; k < c.size(); ++k) {
        const Vec3 a = c[k], e = c[(k + 1) % c.size()] - a;
        const double t = std::clamp(dot(p - a, e) / dot(e, e), 0.0, 1.0);
        if (norm(p - (a + e * t)) < d) {
          d = norm(p - (a + e * t));
          nearest = a + e * t;
        }
      }
      return nearest;
    };
    return {lo, hi, inside, [=](const Vec3& p) { return norm(p - nearest_edge_point(p)); }, nearest_edge_point};
  }
  if (alt == "half_space") {
    const Vec3 x0 = v.vector("point");
    Vec3 n = v.vector("normal");
    if (!(norm(n) > 0.0)) v.fail("normal", "must not be the zero vector");
    n = n / norm(n);
    return {dlo, dhi, [=](const Vec3& p) { return dot(p - x0, n) < 0.0; },
            [=](const Vec3& p) { return std::abs(dot(p - x0, n)); },
            [=](const Vec3& p) { return p - n * dot(p - x0, n); }};
  }
  if (alt == "mesh") {
    auto mesh = std::make_shared<TriangleMesh>(scaled_mesh(v));
    Vec3 lo, hi;
    mesh->bounds(lo, hi);
    return {lo, hi, [mesh](const Vec3& p) { return mesh->contains(p); },
            [mesh](const Vec3& p) { return mesh->distance(p); },
            [mesh](const Vec3& p) {
              Vec3 nearest;
              mesh->distance(p, &nearest);
              return nearest;
            }};
  }
  v.fail("", "shape '" + alt + "' cannot be filled with particles (it is for blocks or walls only)");
}

}  // namespace

// The lattice spacing per axis of a shape (defined below, beside lattice_volume).
static Vec3 lattice_spacing(const std::string& alt, const ParamValues& v, double dp, int dim);

std::vector<Vec3> fill_points(const std::string& alt, const ParamValues& v, double dp, int dim, const Vec3& dlo,
                              const Vec3& dhi) {
  if (alt == "box_walls") v.fail("", "box_walls has no inside to fill; use box for a fluid body");
  const Solid s = solid(alt, v, dim, dlo, dhi);
  if (alt == "box")
    return lattice(s.lo, s.hi, box_lattice(v, dp, dim).spacing, dim, [](const Vec3&) { return Verdict{true}; });
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
  return lattice(s.lo, s.hi + Vec3{dp, dp, dp}, Vec3{dp, dp, dp}, dim, [&](const Vec3& p) {
    if (beyond_domain(p)) return Verdict{false};  // no skip: the points after it may be back in the domain
    return s.inside(p) ? Verdict{true} : Verdict{false, points_within(s.distance(p), dp)};
  });
}

std::vector<Vec3> wall_points(const std::string& alt, const ParamValues& v, double dp, int dim, int layers,
                              const Vec3& dlo, const Vec3& dhi) {
  if (alt == "box_walls") return box_wall_lattice(v, tank_lattice(v, dp, dim), layers, dim);
  // Kept: inside the solid, less than `thickness` from its surface.
  const double thickness = layers * dp;
  const Solid s = solid(alt, v, dim, dlo, dhi);
  const Vec3 spacing = lattice_spacing(alt, v, dp, dim);
  const Vec3 hi = alt == "box" ? s.hi : s.hi + Vec3{dp, dp, dp};
  return lattice(s.lo, hi, spacing, dim, [&](const Vec3& p) {
    const double d = s.distance(p);
    if (!s.inside(p)) return Verdict{false, points_within(d, spacing.x)};
    return d < thickness ? Verdict{true} : Verdict{false, points_within(d - thickness, spacing.x)};
  });
}

std::function<Vec3(const Vec3&)> wall_surface(const std::string& alt, const ParamValues& v, int dim, const Vec3& dlo,
                                              const Vec3& dhi) {
  if (alt != "box_walls") return solid(alt, v, dim, dlo, dhi).surface;
  const Vec3 lo = v.vector("min"), hi = v.vector("max");
  return [=](const Vec3& p) {  // walls outside the box: the nearest point of the box
    Vec3 s = p;
    for (int a = 0; a < dim; ++a) s[a] = std::clamp(p[a], lo[a], hi[a]);
    return s;
  };
}

std::function<bool(const Vec3&)> wall_region(const std::string& alt, const ParamValues& v, double dp, int dim,
                                             int layers, const Vec3& dlo, const Vec3& dhi) {
  if (alt != "box_walls") return solid(alt, v, dim, dlo, dhi).inside;
  const BoxLattice tank = tank_lattice(v, dp, dim);
  const Vec3 lo = v.vector("min"), hi = v.vector("max");
  Vec3 outer_lo = lo, outer_hi = hi;  // the box grown by the walls' thickness across its closed faces
  for (int a = 0; a < dim; ++a) {
    if (face_closed(v, a, '-')) outer_lo[a] -= layers * tank.spacing[a];
    if (face_closed(v, a, '+')) outer_hi[a] += layers * tank.spacing[a];
  }
  return [=](const Vec3& p) {
    bool in_box = true;
    for (int a = 0; a < dim; ++a) {
      if (p[a] < outer_lo[a] || p[a] > outer_hi[a]) return false;
      in_box = in_box && p[a] >= lo[a] && p[a] <= hi[a];
    }
    return !in_box;
  };
}

static Vec3 lattice_spacing(const std::string& alt, const ParamValues& v, double dp, int dim) {
  if (alt == "box") return box_lattice(v, dp, dim).spacing;
  if (alt == "box_walls") return tank_lattice(v, dp, dim).spacing;
  return {dp, dp, dp};
}

double lattice_volume(const std::string& alt, const ParamValues& v, double dp, int dim) {
  const Vec3 s = lattice_spacing(alt, v, dp, dim);
  if (s == Vec3{dp, dp, dp}) return std::pow(dp, dim);
  double volume = 1.0;
  for (int a = 0; a < dim; ++a) volume *= s[a];
  return volume;
}

std::string lattice_adjustment(const std::string& alt, const ParamValues& v, double dp, int dim) {
  if (alt != "box" && alt != "box_walls") return "";
  const BoxLattice b = alt == "box" ? box_lattice(v, dp, dim) : tank_lattice(v, dp, dim);
  const Vec3 lo = v.vector("min"), hi = v.vector("max");
  std::string out;
  for (int a = 0; a < dim; ++a) {
    const std::string axis(1, static_cast<char>('x' + a));
    const double length = hi[a] - lo[a], n = static_cast<double>(b.n[a]);
    std::string change;
    if (b.spacing[a] != dp)
      change = "its " + digits(length) + " m are " + digits(length / dp) + " spacings of " + digits(dp) + " m: " +
               std::to_string(b.n[a]) + " particles at " + digits(b.spacing[a]) + " m";
    else if (b.open_end[a])
      change = "its walls end at " + digits(face_closed(v, a, '-') ? lo[a] + n * dp : hi[a] - n * dp) +
               " m on the open side, not " + digits(face_closed(v, a, '-') ? hi[a] : lo[a]) + " m (" +
               std::to_string(b.n[a]) + " spacings of " + digits(dp) + " m from the closed face)";
    if (!change.empty()) out += std::string(out.empty() ? "" : "; ") + "along " + axis + " " + change;
  }
  return out.empty() ? "" : "the box does not fit a whole number of spacings: " + out;
}

}  // namespace talus
