#include "narrow_phase.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace talus::dda {
namespace {

constexpr double infinity = std::numeric_limits<double>::infinity();
constexpr std::uint64_t id_mask = (1ull << 62) - 1;

std::uint64_t mix(std::uint64_t a, std::uint64_t b) {
  // splitmix64 finaliser over a combination: stable, order-dependent ids.
  std::uint64_t z = a * 0x9e3779b97f4a7c15ull + b + 0x632be59bd9b4e019ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

struct FaceQuery {
  double sep = -infinity;
  int face = -1;
};

struct EdgeQuery {
  double sep = -infinity;
  int edge_a = -1, edge_b = -1;
  Vec3 axis{};
};

// Best face of `ref` as a separating plane for `other`: max over faces of
// (min over other's vertices of the signed distance to the face plane).
FaceQuery query_faces(const PosedBlock& ref, const PosedBlock& other, double margin) {
  FaceQuery q;
  const std::size_t nf = ref.shape->faces.size(), nv = other.shape->vertices.size();
  for (std::size_t f = 0; f < nf; ++f) {
    const Vec3 n = ref.normals[f];
    double lowest = infinity;
    for (std::size_t v = 0; v < nv; ++v) lowest = std::min(lowest, dot(n, other.vertices[v]));
    const double sep = lowest - ref.offsets[f];
    if (sep > q.sep) {
      q.sep = sep;
      q.face = static_cast<int>(f);
      if (sep > margin) return q;  // separated: no need to look further
    }
  }
  return q;
}

EdgeQuery query_edges(const PosedBlock& a, const PosedBlock& b, double margin, NarrowPhaseScratch& scratch) {
  EdgeQuery q;
  const auto& ea = a.shape->edges;
  const auto& eb = b.shape->edges;
  // b's edge data once per pair, not once per edge pair.
  auto& bd = scratch.edges;
  bd.resize(eb.size());
  for (std::size_t j = 0; j < eb.size(); ++j) {
    const Vec3 c = -b.normals[eb[j].f0], d = -b.normals[eb[j].f1];
    const Vec3 pb = b.vertices[eb[j].v0];
    bd[j] = {c, d, cross(d, c), pb, b.vertices[eb[j].v1] - pb};
  }
  for (std::size_t i = 0; i < ea.size(); ++i) {
    const Vec3 pa = a.vertices[ea[i].v0];
    const Vec3 da = a.vertices[ea[i].v1] - pa;
    const Vec3 na0 = a.normals[ea[i].f0], na1 = a.normals[ea[i].f1];
    const Vec3 b_x_a = cross(na1, na0);
    const double la = norm(da);
    for (std::size_t j = 0; j < eb.size(); ++j) {
      const auto& e = bd[j];
      // Do the arcs na0-na1 and c-d cross on the Gauss sphere? Then the edge
      // pair spans a face of the Minkowski difference: a candidate axis.
      const double cba = dot(e.c, b_x_a), dba = dot(e.d, b_x_a);
      if (cba * dba >= 0.0) continue;
      const double adc = dot(na0, e.d_x_c), bdc = dot(na1, e.d_x_c);
      if (adc * bdc >= 0.0 || cba * bdc <= 0.0) continue;
      Vec3 axis = cross(da, e.direction);
      const double len = norm(axis);
      if (len <= 1e-9 * la * norm(e.direction)) continue;  // parallel edges: the face axes cover them
      axis = axis / len;
      if (dot(axis, pa - a.centre) < 0.0) axis = -axis;  // outward from a
      const double sep = dot(axis, e.point - pa);
      if (sep > q.sep) {
        q = {sep, static_cast<int>(i), static_cast<int>(j), axis};
        if (sep > margin) return q;
      }
    }
  }
  return q;
}

// Keeps the part of the polygon with dot(s, p) <= offset (s a unit normal).
// A vertex within `eps` of the plane counts as on it: coincident faces then
// clip to the same points every step instead of a vertex and a crossing a
// rounding error apart, whose number (4 or 8 springs) would flip.
void clip(std::vector<Vec3>& poly, std::vector<std::uint64_t>& ids, const Vec3& s, double offset, std::uint64_t plane,
          double eps, NarrowPhaseScratch& scratch) {
  auto& out = scratch.next;
  auto& out_ids = scratch.next_ids;
  out.clear();
  out_ids.clear();
  const std::size_t n = poly.size();
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = (i + 1) % n;
    const double dp = dot(s, poly[i]) - offset, dq = dot(s, poly[j]) - offset;
    if (dp <= eps) {
      out.push_back(poly[i]);
      out_ids.push_back(ids[i]);
    }
    if ((dp < -eps && dq > eps) || (dp > eps && dq < -eps)) {
      const double t = dp / (dp - dq);
      out.push_back(poly[i] + t * (poly[j] - poly[i]));
      out_ids.push_back(mix(mix(ids[i], ids[j]), plane));
    }
  }
  poly.swap(out);
  ids.swap(out_ids);
}

int face_contact(const PosedBlock& ref, int rf, const PosedBlock& inc, double margin, bool ref_is_a,
                 std::vector<ContactPoint>& out, NarrowPhaseScratch& scratch) {
  const Vec3 n = ref.normals[rf];
  const double d = ref.offsets[rf];
  int incident = 0;
  double most_opposed = infinity;
  for (std::size_t f = 0; f < inc.shape->faces.size(); ++f) {
    const double c = dot(inc.normals[f], n);
    if (c < most_opposed) {
      most_opposed = c;
      incident = static_cast<int>(f);
    }
  }
  auto& poly = scratch.poly;
  auto& ids = scratch.ids;
  poly.clear();
  ids.clear();
  for (int v : inc.shape->faces[incident]) {
    poly.push_back(inc.vertices[v]);
    ids.push_back(static_cast<std::uint64_t>(v));  // an incident vertex keeps its id whatever the face
  }
  const auto& rface = ref.shape->faces[rf];
  const double eps = 1e-3 * margin;
  for (std::size_t k = 0; k < rface.size() && !poly.empty(); ++k) {
    const Vec3 p0 = ref.vertices[rface[k]], p1 = ref.vertices[rface[(k + 1) % rface.size()]];
    Vec3 side = cross(p1 - p0, n);  // outward normal of the side plane through edge k
    side = side / norm(side);
    clip(poly, ids, side, dot(side, p0), 0x5bd1e995ull + (static_cast<std::uint64_t>(rf) << 20) + k, eps, scratch);
  }
  const std::uint64_t kind = ref_is_a ? feature_face_a : feature_face_b;
  const Vec3 normal = ref_is_a ? n : -n;
  const std::size_t first = out.size();
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const double sep = dot(n, poly[i]) - d;
    if (sep > margin) continue;
    ContactPoint c;
    c.point = poly[i] - (0.5 * sep) * n;
    c.normal = normal;
    c.gap = sep;
    c.feature = kind | (mix(ids[i], static_cast<std::uint64_t>(rf)) & id_mask);
    out.push_back(c);
  }
  if (out.size() == first) {
    // Clipping lost everything (the blocks touch at the rim of the face):
    // fall back to the deepest incident vertex.
    double deepest = infinity;
    int best = 0;
    for (std::size_t v = 0; v < inc.shape->vertices.size(); ++v) {
      const double sep = dot(n, inc.vertices[v]) - d;
      if (sep < deepest) {
        deepest = sep;
        best = static_cast<int>(v);
      }
    }
    ContactPoint c;
    c.point = inc.vertices[best] - (0.5 * deepest) * n;
    c.normal = normal;
    c.gap = deepest;
    c.feature = kind | (mix(static_cast<std::uint64_t>(best), static_cast<std::uint64_t>(rf)) & id_mask);
    out.push_back(c);
  }
  const int count = static_cast<int>(out.size() - first);
  double area = 0.0;
  if (count >= 3) {
    Vec3 twice{};
    for (int i = 0; i < count; ++i)
      twice += cross(out[first + i].point, out[first + (i + 1) % count].point);
    area = 0.5 * std::abs(dot(twice, n));
  }
  for (int i = 0; i < count; ++i) {
    out[first + i].area = area / count;
    out[first + i].manifold_size = count;
  }
  return count;
}

// Closest points of segments p1-q1 and p2-q2 (Ericson, Real-Time Collision
// Detection, 5.1.9), clamped to the segments.
void closest_points(const Vec3& p1, const Vec3& q1, const Vec3& p2, const Vec3& q2, Vec3& c1, Vec3& c2) {
  const Vec3 d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
  const double a = dot(d1, d1), e = dot(d2, d2), f = dot(d2, r), c = dot(d1, r), b = dot(d1, d2);
  const double denom = a * e - b * b;
  double s = denom > 1e-300 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
  double t = (b * s + f) / e;
  if (t < 0.0) {
    t = 0.0;
    s = std::clamp(-c / a, 0.0, 1.0);
  } else if (t > 1.0) {
    t = 1.0;
    s = std::clamp((b - c) / a, 0.0, 1.0);
  }
  c1 = p1 + s * d1;
  c2 = p2 + t * d2;
}

}  // namespace

int collide(const PosedBlock& a, const PosedBlock& b, double margin, std::vector<ContactPoint>& out,
            NarrowPhaseScratch& scratch) {
  const FaceQuery fa = query_faces(a, b, margin);
  if (fa.sep > margin) return 0;
  const FaceQuery fb = query_faces(b, a, margin);
  if (fb.sep > margin) return 0;
  const EdgeQuery ee = query_edges(a, b, margin, scratch);
  if (ee.sep > margin) return 0;

  // Hysteresis: prefer faces over edges and a over b unless clearly worse.
  const double scale = std::min(a.shape->radius, b.shape->radius);
  const double best_face = std::max(fa.sep, fb.sep);
  const double tol = 1e-4 * scale + 0.02 * std::abs(best_face);
  if (ee.edge_a >= 0 && ee.sep > best_face + tol) {
    const auto& ea = a.shape->edges[ee.edge_a];
    const auto& eb = b.shape->edges[ee.edge_b];
    Vec3 ca, cb;
    closest_points(a.vertices[ea.v0], a.vertices[ea.v1], b.vertices[eb.v0], b.vertices[eb.v1], ca, cb);
    ContactPoint c;
    c.point = 0.5 * (ca + cb);
    c.normal = ee.axis;
    c.gap = ee.sep;
    c.feature = feature_edges | ((static_cast<std::uint64_t>(ee.edge_a) << 31) | static_cast<std::uint64_t>(ee.edge_b));
    out.push_back(c);
    return 1;
  }
  if (fb.sep > fa.sep + tol) return face_contact(b, fb.face, a, margin, false, out, scratch);
  return face_contact(a, fa.face, b, margin, true, out, scratch);
}

double separation(const PosedBlock& a, const PosedBlock& b) {
  const double big = infinity;
  NarrowPhaseScratch scratch;
  return std::max({query_faces(a, b, big).sep, query_faces(b, a, big).sep, query_edges(a, b, big, scratch).sep});
}

}  // namespace talus::dda
