// Convex polyhedra for rigid blocks: exact mass properties, validation and
// primitives. Header-only so that any plugin (the DDA stage, a fluid-block
// coupling) can use it without linking another plugin.
//
// Mass properties: the solid is split into tetrahedra (reference point, fan
// triangle of a face); for a tetrahedron with vertices 0, a, b, c and
// D = det[a b c]: V = D/6, int x dV = V (a+b+c)/4 and
// int x x^T dV = D/120 (a a^T + b b^T + c c^T + (a+b+c)(a+b+c)^T)
// (Tonon 2004, "Explicit exact formulas for the 3-D tetrahedron inertia tensor").
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "talus/blocks.hpp"
#include "talus/vec3.hpp"

namespace talus::dda {

struct MassProperties {
  double volume = 0.0;               // m^3 (negative if the faces are inverted)
  Vec3 centroid{};                   // m
  std::array<double, 9> inertia{};   // about the centroid per unit density, m^5, row major
};

namespace detail {

inline Vec3 bounds_centre(const std::vector<Vec3>& v, double* diagonal = nullptr) {
  Vec3 lo = v.empty() ? Vec3{} : v[0], hi = lo;
  for (const auto& p : v)
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], p[a]);
      hi[a] = std::max(hi[a], p[a]);
    }
  if (diagonal) *diagonal = norm(hi - lo);
  return 0.5 * (lo + hi);
}

// Newell's normal of a polygon: |n| is twice its area.
inline Vec3 newell_normal(const std::vector<Vec3>& v, const std::vector<int>& face) {
  Vec3 n{};
  for (std::size_t i = 0; i < face.size(); ++i) {
    const Vec3& p = v[face[i]];
    const Vec3& q = v[face[(i + 1) % face.size()]];
    n.x += (p.y - q.y) * (p.z + q.z);
    n.y += (p.z - q.z) * (p.x + q.x);
    n.z += (p.x - q.x) * (p.y + q.y);
  }
  return n;
}

inline std::string str(std::size_t i) { return std::to_string(i); }

}  // namespace detail

inline MassProperties mass_properties(const std::vector<Vec3>& v, const std::vector<std::vector<int>>& faces) {
  const Vec3 ref = detail::bounds_centre(v);  // near the solid: keeps the sums well conditioned
  double volume = 0.0;
  Vec3 first{};
  double c[3][3] = {};
  for (const auto& f : faces)
    for (std::size_t k = 1; k + 1 < f.size(); ++k) {
      const Vec3 a = v[f[0]] - ref, b = v[f[k]] - ref, d = v[f[k + 1]] - ref;
      const double det = dot(a, cross(b, d));
      const Vec3 s = a + b + d;
      volume += det / 6.0;
      first += (det / 24.0) * s;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) c[i][j] += det / 120.0 * (a[i] * a[j] + b[i] * b[j] + d[i] * d[j] + s[i] * s[j]);
    }
  MassProperties mp;
  mp.volume = volume;
  if (volume == 0.0) return mp;
  const Vec3 g = first / volume;
  mp.centroid = ref + g;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) c[i][j] -= volume * g[i] * g[j];  // parallel axis: about the centroid
  const double trace = c[0][0] + c[1][1] + c[2][2];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) mp.inertia[3 * i + j] = (i == j ? trace : 0.0) - c[i][j];
  return mp;
}

// Reverses the faces of a convex primitive whose normal points inwards
// (primitives only: for user input an inverted face is an error).
inline void orient_outward(const std::vector<Vec3>& v, std::vector<std::vector<int>>& faces) {
  Vec3 centre{};  // the vertex mean is inside a convex solid (the box centre need not be)
  for (const auto& p : v) centre += p / static_cast<double>(v.size());
  for (auto& f : faces)
    if (dot(detail::newell_normal(v, f), v[f[0]] - centre) < 0.0) std::reverse(f.begin(), f.end());
}

inline void box_polyhedron(const Vec3& lo, const Vec3& hi, std::vector<Vec3>& v, std::vector<std::vector<int>>& f) {
  v.clear();
  for (int k = 0; k < 8; ++k) v.push_back({(k & 1) ? hi.x : lo.x, (k & 2) ? hi.y : lo.y, (k & 4) ? hi.z : lo.z});
  f = {{0, 1, 3, 2}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 3, 7, 5}};
  orient_outward(v, f);
}

// Right-angled prism: triangle (0,0), (length,0), (0,height) in x-z, extruded along +y.
inline void wedge_polyhedron(const Vec3& origin, double length, double height, double width, std::vector<Vec3>& v,
                             std::vector<std::vector<int>>& f) {
  v.clear();
  for (double y : {0.0, width})
    for (const Vec3& p : {Vec3{0, y, 0}, Vec3{length, y, 0}, Vec3{0, y, height}}) v.push_back(origin + p);
  f = {{0, 1, 2}, {3, 4, 5}, {0, 1, 4, 3}, {1, 2, 5, 4}, {2, 0, 3, 5}};
  orient_outward(v, f);
}

inline void tetrahedron_polyhedron(const std::vector<Vec3>& corners, std::vector<Vec3>& v,
                                   std::vector<std::vector<int>>& f) {
  v = corners;
  if (dot(v[1] - v[0], cross(v[2] - v[0], v[3] - v[0])) < 0.0) std::swap(v[1], v[2]);
  f = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};  // outward for a positive orientation
}

// Merges vertices closer than `tol` (STL files repeat every corner per triangle);
// remaps the faces.
inline void weld_vertices(std::vector<Vec3>& v, std::vector<std::vector<int>>& faces, double tol) {
  std::vector<int> order(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) order[i] = static_cast<int>(i);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return v[a].x < v[b].x; });
  std::vector<int> remap(v.size(), -1);
  std::vector<Vec3> out;
  for (std::size_t s = 0; s < order.size(); ++s) {
    const int i = order[s];
    if (remap[i] >= 0) continue;
    remap[i] = static_cast<int>(out.size());
    for (std::size_t t = s + 1; t < order.size() && v[order[t]].x - v[i].x <= tol; ++t)
      if (remap[order[t]] < 0 && norm(v[order[t]] - v[i]) <= tol) remap[order[t]] = remap[i];
    out.push_back(v[i]);
  }
  for (auto& f : faces) {
    for (int& k : f) k = remap[k];
    f.erase(std::unique(f.begin(), f.end()), f.end());
    while (f.size() > 1 && f.front() == f.back()) f.pop_back();
  }
  v = std::move(out);
}

// Checks that (vertices, faces) bound a closed convex solid with faces
// counter-clockwise seen from outside, then builds `out` in the body frame
// (centroid at the origin; coplanar faces merged into one convex polygon;
// normals, plane offsets and edges filled) and the mass properties (centroid
// in the input frame). Returns an empty string, or what is wrong.
inline std::string make_convex_polyhedron(std::vector<Vec3> v, std::vector<std::vector<int>> faces, Polyhedron& out,
                                          MassProperties& mp) {
  using detail::str;
  const std::size_t nv = v.size();
  if (nv < 4) return "a polyhedron needs at least 4 vertices, got " + str(nv);
  if (faces.size() < 4) return "a closed polyhedron needs at least 4 faces, got " + str(faces.size());
  for (std::size_t k = 0; k < faces.size(); ++k) {
    const auto& f = faces[k];
    if (f.size() < 3) return "face " + str(k) + " has " + str(f.size()) + " vertices; a face needs at least 3";
    for (std::size_t i = 0; i < f.size(); ++i) {
      if (f[i] < 0 || static_cast<std::size_t>(f[i]) >= nv)
        return "face " + str(k) + " names vertex " + std::to_string(f[i]) + "; there are " + str(nv) + " vertices";
      for (std::size_t j = 0; j < i; ++j)
        if (f[j] == f[i]) return "face " + str(k) + " repeats vertex " + std::to_string(f[i]);
    }
  }
  for (const auto& p : v)
    if (!is_finite(p)) return "a vertex is not a finite number";
  double size = 0.0;
  detail::bounds_centre(v, &size);
  if (!(size > 0.0)) return "zero volume: all vertices coincide";
  const double tol = 1e-6 * size;  // coordinates typed with ~7 digits must pass

  // Closed and consistently oriented: every directed edge once, its reverse once.
  std::vector<std::pair<int, int>> directed;
  for (const auto& f : faces)
    for (std::size_t i = 0; i < f.size(); ++i) directed.emplace_back(f[i], f[(i + 1) % f.size()]);
  std::sort(directed.begin(), directed.end());
  for (std::size_t i = 0; i + 1 < directed.size(); ++i)
    if (directed[i] == directed[i + 1])
      return "faces are inconsistently oriented: edge " + std::to_string(directed[i].first) + "-" +
             std::to_string(directed[i].second) +
             " runs the same way in two faces (an inverted face); list every face counter-clockwise seen from outside";
  for (const auto& [a, b] : directed)
    if (!std::binary_search(directed.begin(), directed.end(), std::make_pair(b, a)))
      return "the surface is not closed: edge " + std::to_string(a) + "-" + std::to_string(b) +
             " belongs to one face only";
  std::vector<char> used(nv, 0);
  for (const auto& [a, b] : directed) used[a] = 1;
  for (std::size_t i = 0; i < nv; ++i)
    if (!used[i]) return "vertex " + str(i) + " belongs to no face";

  mp = mass_properties(v, faces);
  if (std::abs(mp.volume) <= 1e-12 * size * size * size) return "zero volume: the vertices are (nearly) coplanar";
  if (mp.volume < 0.0)
    return "the faces are inverted (clockwise seen from outside); list every face counter-clockwise seen from outside";

  // Planar faces, and every vertex behind every face plane (convexity).
  std::vector<Vec3> normal(faces.size());
  std::vector<double> offset(faces.size());
  for (std::size_t k = 0; k < faces.size(); ++k) {
    const Vec3 n = detail::newell_normal(v, faces[k]);
    const double len = norm(n);
    if (!(len > 1e-12 * size * size)) return "face " + str(k) + " has zero area";
    normal[k] = n / len;
    double d = 0.0;
    for (int i : faces[k]) d += dot(normal[k], v[i]);
    offset[k] = d / faces[k].size();
    for (int i : faces[k])
      if (std::abs(dot(normal[k], v[i]) - offset[k]) > tol) return "face " + str(k) + " is not planar";
  }
  for (std::size_t k = 0; k < faces.size(); ++k)
    for (std::size_t i = 0; i < nv; ++i)
      if (dot(normal[k], v[i]) - offset[k] > tol)
        return "the block is not convex: vertex " + str(i) + " lies outside the plane of face " + str(k) +
               " (split it into convex blocks)";

  // Merge coplanar faces into one polygon: the convex hull of their vertices
  // in the plane, counter-clockwise about the outward normal.
  std::vector<int> group(faces.size(), -1);
  std::vector<std::vector<int>> merged;
  std::vector<Vec3> merged_normal;
  for (std::size_t k = 0; k < faces.size(); ++k) {
    if (group[k] >= 0) continue;
    group[k] = static_cast<int>(merged.size());
    std::vector<int> ids(faces[k].begin(), faces[k].end());
    for (std::size_t m = k + 1; m < faces.size(); ++m)
      if (group[m] < 0 && dot(normal[k], normal[m]) > 1.0 - 1e-9 && std::abs(offset[k] - offset[m]) <= tol) {
        group[m] = group[k];
        ids.insert(ids.end(), faces[m].begin(), faces[m].end());
      }
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    const Vec3 n = normal[k];
    const Vec3 axis = std::abs(n.x) < 0.6 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
    const Vec3 u = cross(axis, n) / norm(cross(axis, n));
    const Vec3 w = cross(n, u);  // (u, w, n) right-handed: CCW in (u, w) is CCW seen from outside
    std::sort(ids.begin(), ids.end(), [&](int a, int b) {
      const double ua = dot(v[a], u), ub = dot(v[b], u);
      return ua != ub ? ua < ub : dot(v[a], w) < dot(v[b], w);
    });
    auto turn = [&](int o, int a, int b) {
      const Vec3 oa = v[a] - v[o], ob = v[b] - v[o];
      return dot(cross(oa, ob), n);
    };
    // Andrew's monotone chain; drops collinear points (turn <= tol * size).
    std::vector<int> hull(2 * ids.size());
    std::size_t h = 0;
    for (std::size_t i = 0; i < ids.size(); ++i) {
      while (h >= 2 && turn(hull[h - 2], hull[h - 1], ids[i]) <= tol * size) --h;
      hull[h++] = ids[i];
    }
    for (std::size_t i = ids.size() - 1, lower = h + 1; i-- > 0;) {
      while (h >= lower && turn(hull[h - 2], hull[h - 1], ids[i]) <= tol * size) --h;
      hull[h++] = ids[i];
    }
    hull.resize(h - 1);
    if (hull.size() < 3) return "face " + str(k) + " has zero area";
    merged.push_back(std::move(hull));
    merged_normal.push_back(n);
  }

  // Keep only vertices that are corners of the merged faces; body frame.
  std::vector<int> remap(nv, -1);
  out = Polyhedron{};
  for (auto& f : merged)
    for (int& i : f) {
      if (remap[i] < 0) {
        remap[i] = static_cast<int>(out.vertices.size());
        out.vertices.push_back(v[i] - mp.centroid);
      }
      i = remap[i];
    }
  out.faces = std::move(merged);
  out.normals = std::move(merged_normal);
  out.offsets.resize(out.faces.size());
  for (std::size_t k = 0; k < out.faces.size(); ++k) {
    double d = 0.0;
    for (int i : out.faces[k]) d += dot(out.normals[k], out.vertices[i]);
    out.offsets[k] = d / out.faces[k].size();
  }
  struct Directed {
    int a, b, face;
  };
  std::vector<Directed> half;
  for (std::size_t k = 0; k < out.faces.size(); ++k) {
    const auto& f = out.faces[k];
    for (std::size_t i = 0; i < f.size(); ++i) half.push_back({f[i], f[(i + 1) % f.size()], static_cast<int>(k)});
  }
  auto less = [](const Directed& x, const Directed& y) { return x.a != y.a ? x.a < y.a : x.b < y.b; };
  std::sort(half.begin(), half.end(), less);
  for (const auto& e : half) {
    if (e.a > e.b) continue;
    const auto it = std::lower_bound(half.begin(), half.end(), Directed{e.b, e.a, 0}, less);
    if (it == half.end() || it->a != e.b || it->b != e.a)
      return "degenerate geometry: merging coplanar faces left edge " + str(e.a) + "-" + str(e.b) + " open";
    out.edges.push_back({e.a, e.b, e.face, it->face});
  }
  for (const auto& p : out.vertices) out.radius = std::max(out.radius, norm(p));
  return {};
}

// Largest signed distance of p (body frame) to the face planes: exact inside
// (negative depth), a lower bound of the distance outside.
inline double plane_distance(const Polyhedron& poly, const Vec3& p) {
  double d = -1e300;
  for (std::size_t k = 0; k < poly.normals.size(); ++k) d = std::max(d, dot(poly.normals[k], p) - poly.offsets[k]);
  return d;
}

}  // namespace talus::dda
