// Contact detection against brute-force geometry on random convex pairs, and
// the degenerate cases: coplanar faces, vertex on an edge, crossed edges,
// resting contact with stable feature ids.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "narrow_phase.hpp"
#include "talus/dda/polyhedron.hpp"

using namespace talus;
using namespace talus::dda;

namespace {

struct Posed {
  Polyhedron shape;
  std::vector<Vec3> v, n;
  std::vector<double> d;
  Vec3 x{};

  Posed(const std::vector<Vec3>& verts, const std::vector<std::vector<int>>& faces) {
    MassProperties mp;
    const std::string problem = make_convex_polyhedron(verts, faces, shape, mp);
    EXPECT_EQ(problem, "");
    place(mp.centroid, {});
  }
  void place(const Vec3& position, const Quaternion& q) {
    x = position;
    v.clear();
    n.clear();
    d.clear();
    for (const auto& p : shape.vertices) v.push_back(x + rotate(q, p));
    for (std::size_t f = 0; f < shape.faces.size(); ++f) {
      n.push_back(rotate(q, shape.normals[f]));
      d.push_back(shape.offsets[f] + dot(n.back(), x));
    }
  }
  PosedBlock view() const { return {&shape, v.data(), n.data(), d.data(), x}; }
  double distance_to_planes(const Vec3& p) const {
    double m = -1e300;
    for (std::size_t f = 0; f < n.size(); ++f) m = std::max(m, dot(n[f], p) - d[f]);
    return m;
  }
};

Posed box(Vec3 lo, Vec3 hi) {
  std::vector<Vec3> v;
  std::vector<std::vector<int>> f;
  box_polyhedron(lo, hi, v, f);
  return Posed(v, f);
}

// Exact intersection test for convex polyhedra: a vertex of one inside the
// other, or an edge of one crossing a face of the other.
bool edges_cross_faces(const Posed& a, const Posed& b) {
  for (const auto& e : a.shape.edges) {
    const Vec3 p = a.v[e.v0], q = a.v[e.v1];
    for (std::size_t f = 0; f < b.n.size(); ++f) {
      const double dp = dot(b.n[f], p) - b.d[f], dq = dot(b.n[f], q) - b.d[f];
      if (dp * dq >= 0.0) continue;
      const Vec3 x = p + (dp / (dp - dq)) * (q - p);
      const auto& face = b.shape.faces[f];
      bool inside = true;
      for (std::size_t k = 0; k < face.size() && inside; ++k) {
        const Vec3 v0 = b.v[face[k]], v1 = b.v[face[(k + 1) % face.size()]];
        inside = dot(cross(v1 - v0, x - v0), b.n[f]) >= 0.0;
      }
      if (inside) return true;
    }
  }
  return false;
}

bool brute_intersect(const Posed& a, const Posed& b) {
  for (const auto& p : a.v)
    if (b.distance_to_planes(p) < 0.0) return true;
  for (const auto& p : b.v)
    if (a.distance_to_planes(p) < 0.0) return true;
  return edges_cross_faces(a, b) || edges_cross_faces(b, a);
}

// Full separating-axis test: every face normal and every edge-edge cross
// product, supports by scanning all vertices (no Gauss-map pruning).
double brute_separation(const Posed& a, const Posed& b) {
  auto gap_along = [&](Vec3 axis) {
    double amax = -1e300, bmin = 1e300, amin = 1e300, bmax = -1e300;
    for (const auto& p : a.v) amax = std::max(amax, dot(axis, p)), amin = std::min(amin, dot(axis, p));
    for (const auto& p : b.v) bmin = std::min(bmin, dot(axis, p)), bmax = std::max(bmax, dot(axis, p));
    return std::max(bmin - amax, amin - bmax);  // either orientation
  };
  double best = -1e300;
  for (const auto& n : a.n) best = std::max(best, gap_along(n));
  for (const auto& n : b.n) best = std::max(best, gap_along(n));
  for (const auto& ea : a.shape.edges)
    for (const auto& eb : b.shape.edges) {
      const Vec3 c = cross(a.v[ea.v1] - a.v[ea.v0], b.v[eb.v1] - b.v[eb.v0]);
      if (norm(c) < 1e-9) continue;
      best = std::max(best, gap_along(c / norm(c)));
    }
  return best;
}

Quaternion random_rotation(std::mt19937& rng) {
  std::normal_distribution<double> g;
  return normalised({g(rng), g(rng), g(rng), g(rng)});
}

Posed random_shape(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.3, 1.5), s(-1.0, 1.0);
  std::vector<Vec3> v;
  std::vector<std::vector<int>> f;
  switch (rng() % 3) {
    case 0: box_polyhedron({0, 0, 0}, {u(rng), u(rng), u(rng)}, v, f); break;
    case 1: wedge_polyhedron({0, 0, 0}, u(rng), u(rng), u(rng), v, f); break;
    default: {
      std::vector<Vec3> c;
      do {
        c = {{s(rng), s(rng), s(rng)}, {s(rng), s(rng), s(rng)}, {s(rng), s(rng), s(rng)}, {s(rng), s(rng), s(rng)}};
      } while (std::abs(dot(c[1] - c[0], cross(c[2] - c[0], c[3] - c[0]))) < 0.05);
      tetrahedron_polyhedron(c, v, f);
    }
  }
  return Posed(v, f);
}

}  // namespace

TEST(DdaNarrowPhase, RandomConvexPairsMatchBruteForce) {
  std::mt19937 rng(2024);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), reach(0.2, 1.1);
  int intersecting = 0, separated = 0;
  NarrowPhaseScratch scratch;
  for (int trial = 0; trial < 3000; ++trial) {
    Posed a = random_shape(rng), b = random_shape(rng);
    a.place({0, 0, 0}, random_rotation(rng));
    Vec3 dir{unit(rng), unit(rng), unit(rng)};
    dir = dir / norm(dir);
    b.place(reach(rng) * (a.shape.radius + b.shape.radius) * dir, random_rotation(rng));

    // Overlapping: both give the penetration depth (the minimum over all
    // axes); apart: both are positive (a separating axis exists), though not
    // necessarily the same lower bound of the distance.
    const double sep = separation(a.view(), b.view()), brute = brute_separation(a, b);
    if (sep < 0.0 || brute < 0.0) {
      ASSERT_NEAR(sep, brute, 1e-9) << "trial " << trial;
    }
    if (std::abs(sep) < 1e-7) continue;  // grazing: either answer is right
    const bool hit = brute_intersect(a, b);
    ASSERT_EQ(sep < 0.0, hit) << "trial " << trial << " sep " << sep;
    std::vector<ContactPoint> points;
    const int count = collide(a.view(), b.view(), 0.0, points, scratch);
    ASSERT_EQ(count > 0, hit) << "trial " << trial;
    if (!hit) {
      ++separated;
      continue;
    }
    ++intersecting;
    const Vec3 n = points[0].normal;
    EXPECT_NEAR(norm(n), 1.0, 1e-12);
    double deepest = 0.0;
    for (const auto& c : points) {
      // Every point lies in the overlap, within half its gap of each surface.
      EXPECT_LE(a.distance_to_planes(c.point), 0.5 * std::abs(c.gap) + 1e-9) << "trial " << trial;
      EXPECT_LE(b.distance_to_planes(c.point), 0.5 * std::abs(c.gap) + 1e-9) << "trial " << trial;
      EXPECT_LE(c.gap, 1e-12);
      deepest = std::min(deepest, c.gap);
    }
    // The deepest point's gap is the penetration depth, up to the hysteresis
    // that prefers faces and block a (twice 1e-4 r_min + 2 % of the depth).
    const double hysteresis = 2.0 * (1e-4 * std::min(a.shape.radius, b.shape.radius) + 0.021 * std::abs(sep));
    EXPECT_NEAR(deepest, sep, hysteresis) << "trial " << trial;
    // The normal is (nearly) the direction of least overlap, and pushing b
    // out along it by that overlap separates the pair.
    double amax = -1e300, bmin = 1e300;
    for (const auto& p : a.v) amax = std::max(amax, dot(n, p));
    for (const auto& p : b.v) bmin = std::min(bmin, dot(n, p));
    const double overlap = amax - bmin;
    EXPECT_LE(overlap, -sep + hysteresis) << "trial " << trial;
    Posed moved = b;
    const Vec3 shift = (overlap * (1.0 + 1e-6) + 1e-9) * n;
    for (auto& p : moved.v) p += shift;
    for (std::size_t f = 0; f < moved.n.size(); ++f) moved.d[f] += dot(moved.n[f], shift);
    EXPECT_FALSE(brute_intersect(a, moved)) << "trial " << trial;
  }
  EXPECT_GT(intersecting, 500);
  EXPECT_GT(separated, 500);
}

TEST(DdaNarrowPhase, CoplanarFacesGiveTheOverlapRectangle) {
  Posed base = box({-2, -2, -1}, {2, 2, 0});
  Posed top = box({0.5, 0.5, -0.001}, {1.5, 1.5, 0.999});
  NarrowPhaseScratch scratch;
  std::vector<ContactPoint> points;
  ASSERT_EQ(collide(base.view(), top.view(), 0.01, points, scratch), 4);
  double area = 0.0;
  for (const auto& c : points) {
    EXPECT_NEAR(c.gap, -0.001, 1e-12);
    EXPECT_NEAR(norm(c.normal - Vec3{0, 0, 1}), 0.0, 1e-12);
    area += c.area;
  }
  EXPECT_NEAR(area, 1.0, 1e-9);
  // Overhanging the edge of the base: the manifold is clipped to the overlap.
  Posed over = box({1.5, -0.5, -0.001}, {2.5, 0.5, 0.999});
  points.clear();
  ASSERT_EQ(collide(base.view(), over.view(), 0.01, points, scratch), 4);
  area = 0.0;
  for (const auto& c : points) {
    EXPECT_LE(c.point.x, 2.0 + 1e-12);
    area += c.area;
  }
  EXPECT_NEAR(area, 0.5, 1e-9);
  // Exactly touching (zero gap) is a contact within the margin, and a gap
  // above the margin is none.
  Posed touching = box({0, 0, 0}, {1, 1, 1});
  points.clear();
  EXPECT_EQ(collide(base.view(), touching.view(), 1e-6, points, scratch), 4);
  for (const auto& c : points) EXPECT_NEAR(c.gap, 0.0, 1e-15);
  Posed above = box({0, 0, 0.01}, {1, 1, 1.01});
  points.clear();
  EXPECT_EQ(collide(base.view(), above.view(), 1e-3, points, scratch), 0);
}

TEST(DdaNarrowPhase, VertexOnEdgeAndCrossedEdges) {
  NarrowPhaseScratch scratch;
  std::vector<ContactPoint> points;
  // A tetrahedron whose apex sits exactly on the top edge of a box.
  Posed b = box({-1, -1, -1}, {1, 1, 0});
  std::vector<Vec3> v;
  std::vector<std::vector<int>> f;
  tetrahedron_polyhedron({{1, 0, -0.01}, {2, -1, 1}, {2, 1, 1}, {3, 0, 1}}, v, f);
  Posed t(v, f);
  EXPECT_GT(collide(b.view(), t.view(), 0.05, points, scratch), 0);
  for (const auto& c : points) EXPECT_LE(c.gap, 0.05);
  // Two long bars crossing at right angles, edge on edge.
  points.clear();
  Posed lower = box({-2, -0.1, -0.1}, {2, 0.1, 0.1});
  Posed upper(lower);
  const double s = std::sqrt(0.5);
  upper.place({0, 0, 0.1 * std::sqrt(2.0) + 0.1 - 0.002}, {s, 0, 0, s} /* 90 deg about z */);
  Quaternion roll{std::cos(M_PI / 8), std::sin(M_PI / 8), 0, 0};  // 45 deg about x: an edge points down
  upper.place({0, 0, 0.1 * std::sqrt(2.0) + 0.1 - 0.002}, Quaternion{s, 0, 0, s} * roll);
  ASSERT_EQ(collide(lower.view(), upper.view(), 0.01, points, scratch), 2);  // edge on a face: two points
  // Rolled both: edge on edge -> a single edge-edge point.
  points.clear();
  Posed lower_rolled(lower);
  lower_rolled.place({0, 0, 0}, roll);
  upper.place({0, 0, 0.2 * std::sqrt(2.0) - 0.002}, Quaternion{s, 0, 0, s} * roll);
  ASSERT_EQ(collide(lower_rolled.view(), upper.view(), 0.01, points, scratch), 1);
  EXPECT_EQ(points[0].feature >> 62, feature_edges >> 62);
  EXPECT_NEAR(points[0].gap, -0.002, 1e-9);
  EXPECT_NEAR(norm(points[0].point - Vec3{0, 0, 0.1 * std::sqrt(2.0) - 0.001}), 0.0, 1e-9);
  EXPECT_NEAR(std::abs(points[0].normal.z), 1.0, 1e-9);
}

TEST(DdaNarrowPhase, RestingContactKeepsItsFeatureIds) {
  NarrowPhaseScratch scratch;
  Posed base = box({-2, -2, -1}, {2, 2, 0});
  Posed top = box({0, 0, 0}, {1, 1, 1});
  std::vector<std::uint64_t> first;
  for (int k = 0; k < 20; ++k) {
    // Tiny jitter of a resting block: same features every time.
    const double e = 1e-7 * std::sin(k);
    const Quaternion q = from_rotation_vector({e, -e, 0.5 * e});
    top.place({0.5 + e, 0.5, 0.5 - 1e-5}, q);
    std::vector<ContactPoint> points;
    ASSERT_EQ(collide(base.view(), top.view(), 1e-3, points, scratch), 4);
    std::vector<std::uint64_t> ids;
    for (const auto& c : points) ids.push_back(c.feature);
    std::sort(ids.begin(), ids.end());
    EXPECT_EQ(std::unique(ids.begin(), ids.end()), ids.end());
    if (k == 0)
      first = ids;
    else
      EXPECT_EQ(ids, first);
  }
}

#include "broad_phase.hpp"

TEST(DdaBroadPhase, FindsExactlyTheOverlappingBoxes) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> pos(-3.0, 3.0), ext(0.05, 0.4);
  std::vector<Vec3> lo, hi;
  std::vector<std::uint8_t> active;
  for (int i = 0; i < 600; ++i) {
    const Vec3 c{pos(rng), pos(rng), pos(rng)}, e{ext(rng), ext(rng), ext(rng)};
    lo.push_back(c - e);
    hi.push_back(c + e);
    active.push_back(i % 7 != 0);
  }
  // Large fixed blocks: a floor and a wall.
  lo.push_back({-4, -4, -4});
  hi.push_back({4, 4, -2.5});
  active.push_back(0);
  lo.push_back({-4, -4, -4});
  hi.push_back({-2.8, 4, 4});
  active.push_back(0);
  BroadPhase broad;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs, brute;
  broad.find_pairs(lo, hi, active, pairs);
  for (std::uint32_t i = 0; i < lo.size(); ++i)
    for (std::uint32_t j = i + 1; j < lo.size(); ++j) {
      bool o = active[i] || active[j];
      for (int a = 0; a < 3 && o; ++a) o = lo[i][a] <= hi[j][a] && lo[j][a] <= hi[i][a];
      if (o) brute.emplace_back(i, j);
    }
  EXPECT_GT(brute.size(), 100u);
  EXPECT_EQ(pairs, brute);
}
