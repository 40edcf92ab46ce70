// Lattice filling of shapes and wall layers.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "talus/error.hpp"
#include "talus/geometry.hpp"
#include "talus/mesh.hpp"
#include "talus/motion.hpp"
#include "process.hpp"

namespace talus {
namespace {

ParamValues shape(const std::string& json, int dim = 3) {
  ParamSet body{"body", "test body"};
  declare_shape(body);
  return params_from_json(body, json, dim);
}

TEST(Geometry, BoxIsFilledWithSpacingDpHalfASpacingInsideTheFaces) {
  const ParamValues b = shape(R"({"shape": {"box": {"min": [0, 0], "max": [0.4, 0.2]}}})", 2);
  const auto pts = fill_points("box", b.alternative_values("shape"), 0.05, 2, {}, {});
  ASSERT_EQ(pts.size(), 8u * 4u);
  EXPECT_DOUBLE_EQ(pts.front().x, 0.025);
  EXPECT_DOUBLE_EQ(pts.front().y, 0.025);
  EXPECT_DOUBLE_EQ(pts.back().x, 0.375);
  EXPECT_EQ(pts.back().z, 0.0);
}

// 0.161 m is 16.1 spacings of 0.01 m: 16 particles at 0.0100625 m, half a
// spacing inside both faces, so the box holds exactly its volume; the
// adjustment is said, and the whole-numbered axis keeps dp.
TEST(Geometry, BoxNotAWholeNumberOfSpacingsKeepsItsFaces) {
  const ParamValues b = shape(R"({"shape": {"box": {"min": [0.3, 0], "max": [0.461, 0.1]}}})", 2);
  const ParamValues& box = b.alternative_values("shape");
  const double dp = 0.01, sx = 0.161 / 16;
  const auto pts = fill_points("box", box, dp, 2, {}, {});
  ASSERT_EQ(pts.size(), 16u * 10u);
  EXPECT_NEAR(pts.front().x, 0.3 + 0.5 * sx, 1e-15);
  EXPECT_NEAR(pts[15].x, 0.461 - 0.5 * sx, 1e-15);
  EXPECT_NEAR(pts.back().y, 0.1 - 0.5 * dp, 1e-15);
  EXPECT_NEAR(lattice_volume("box", box, dp, 2) * pts.size(), 0.161 * 0.1, 1e-15);
  const std::string note = lattice_adjustment("box", box, dp, 2);
  EXPECT_NE(note.find("along x its 0.161 m are 16.1 spacings of 0.01 m: 16 particles at 0.0100625 m"),
            std::string::npos)
      << note;
  EXPECT_EQ(note.find("along y"), std::string::npos) << note;
  const ParamValues whole = shape(R"({"shape": {"box": {"min": [0, 0], "max": [0.4, 0.2]}}})", 2);
  EXPECT_EQ(lattice_adjustment("box", whole.alternative_values("shape"), 0.05, 2), "");
  EXPECT_EQ(lattice_volume("box", whole.alternative_values("shape"), 0.05, 2), std::pow(0.05, 2));
}

// 1.5 spacings would be one particle 50 % wider than dp; exactly one spacing is a staircase's column.
TEST(Geometry, BoxUnderTwoSpacingsIsRefusedUnlessExactlyOne) {
  const ParamValues column = shape(R"({"shape": {"box": {"min": [0.7, 0], "max": [0.71, 0.2]}}})", 2);
  EXPECT_EQ(fill_points("box", column.alternative_values("shape"), 0.01, 2, {}, {}).size(), 20u);
  const ParamValues b = shape(R"({"shape": {"box": {"min": [0, 0], "max": [0.015, 0.2]}}})", 2);
  try {
    fill_points("box", b.alternative_values("shape"), 0.01, 2, {}, {});
    ADD_FAILURE() << "a box 1.5 spacings wide was filled";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/shape/box/max: the box spans 0.015 m along x, less than two particle "
                                         "spacings (2 x 0.01 m) and not exactly one"),
              std::string::npos)
        << e.what();
  }
}

// The walls of a tank 1.05 m wide (10.5 spacings): their first layers lie
// half a spacing outside the stated faces whichever face is open (the box's
// adjusted spacing with both x faces closed, dp from the closed face with one
// open), and the mirrored tank has the mirrored walls.
TEST(Geometry, BoxWallsLieOnTheirFacesWhicheverFaceIsOpen) {
  const double dp = 0.1, s = 1.05 / 11;
  for (const char* open : {"-x", "+x", "+y"}) {
    const std::string json = R"({"shape": {"box_walls": {"min": [0, 0], "max": [1.05, 0.5], "open": [")" +
                             std::string(open) + R"("]}}})";
    const ParamValues b = shape(json, 2);
    const auto pts = wall_points("box_walls", b.alternative_values("shape"), dp, 2, 2, {}, {});
    double inner_minus = -1e9, inner_plus = 1e9;
    for (const auto& p : pts) {
      if (p.y < 0.0 || p.y > 0.5) continue;  // the floor and the lid
      if (p.x < 0.5) inner_minus = std::max(inner_minus, p.x);
      if (p.x > 0.5) inner_plus = std::min(inner_plus, p.x);
    }
    const double spacing = std::string(open) == "+y" ? s : dp;
    if (std::string(open) != "-x") EXPECT_NEAR(inner_minus, -0.5 * spacing, 1e-14) << open;
    if (std::string(open) != "+x") EXPECT_NEAR(inner_plus, 1.05 + 0.5 * spacing, 1e-14) << open;
  }
  auto by_x_then_y = [](const Vec3& a, const Vec3& c) { return a.x != c.x ? a.x < c.x : a.y < c.y; };
  auto walls = [&](const char* json) {
    const ParamValues b = shape(json, 2);
    auto pts = wall_points("box_walls", b.alternative_values("shape"), dp, 2, 2, {}, {});
    std::sort(pts.begin(), pts.end(), by_x_then_y);
    return pts;
  };
  const auto left = walls(R"({"shape": {"box_walls": {"min": [0, 0], "max": [1.05, 0.5], "open": ["-x"]}}})");
  auto right = walls(R"({"shape": {"box_walls": {"min": [-1.05, 0], "max": [0, 0.5], "open": ["+x"]}}})");
  for (auto& p : right) p.x = -p.x;
  std::sort(right.begin(), right.end(), by_x_then_y);
  ASSERT_EQ(left.size(), right.size());
  for (std::size_t k = 0; k < left.size(); ++k) {
    EXPECT_NEAR(left[k].x, right[k].x, 1e-14);
    EXPECT_NEAR(left[k].y, right[k].y, 1e-14);
  }
}

TEST(Geometry, SphereVolumeConverges) {
  const ParamValues b = shape(R"({"shape": {"sphere": {"centre": [0, 0, 0], "radius": 0.5}}})");
  const double dp = 0.02;
  const auto pts = fill_points("sphere", b.alternative_values("shape"), dp, 3, {}, {});
  const double volume = pts.size() * dp * dp * dp;
  EXPECT_NEAR(volume, 4.0 / 3.0 * std::numbers::pi * 0.125, 0.01 * 0.5236);
}

TEST(Geometry, BoxWallsSurroundTheTankExceptOpenFaces) {
  const ParamValues b = shape(R"({"shape": {"box_walls": {"min": [0, 0], "max": [1, 0.5], "open": ["+y"]}}})", 2);
  const double dp = 0.1;
  const auto pts = wall_points("box_walls", b.alternative_values("shape"), dp, 2, 2, {}, {});
  // Bottom: (10 + 2*2) * 2 layers; sides: 5 * 2 layers * 2 sides.
  EXPECT_EQ(pts.size(), 14u * 2u + 5u * 2u * 2u);
  for (const auto& p : pts) {
    EXPECT_FALSE(p.x > 0 && p.x < 1 && p.y > 0 && p.y < 0.5) << "wall particle inside the tank";
    EXPECT_LE(p.y, 0.5);  // open top
    EXPECT_GE(p.x, -0.2);
  }
}

TEST(Geometry, BoxWallsCornersMustBeInOrder) {
  EXPECT_THROW(shape(R"({"shape": {"box_walls": {"min": [2147483648, 0], "max": [400, 1]}}})", 2), InputError);
  EXPECT_THROW(shape(R"({"shape": {"box_walls": {"min": [0, 0, 9e15], "max": [1, 1, 1]}}})"), InputError);
}

TEST(Geometry, BoxWallsCannotBeFilled) {
  const ParamValues b = shape(R"({"shape": {"box_walls": {"min": [0, 0], "max": [1, 1]}}})", 2);
  EXPECT_THROW(fill_points("box_walls", b.alternative_values("shape"), 0.1, 2, {}, {}), InputError);
}

// An L-shaped release area: the unit square without its upper-right quarter.
constexpr const char* l_shape = R"({"shape": {"polygon": {"vertices": [[0, 0], [1, 0], [1, 0.5], [0.5, 0.5],
                                                                        [0.5, 1], [0, 1]]}}})";

TEST(Geometry, PolygonIsFilledInsideItsCornersOnly) {
  const ParamValues b = shape(l_shape, 2);
  const double dp = 0.05;
  const auto pts = fill_points("polygon", b.alternative_values("shape"), dp, 2, {}, {});
  // Lattice-aligned: the area 0.75 holds exactly 0.75 / dp^2 particles.
  EXPECT_EQ(pts.size(), 300u);
  for (const auto& p : pts) EXPECT_FALSE(p.x > 0.5 && p.y > 0.5) << "particle in the notch at " << p.x << ", " << p.y;
  // The same corners in the other sense give the same points.
  const ParamValues r = shape(R"({"shape": {"polygon": {"vertices": [[0, 1], [0.5, 1], [0.5, 0.5], [1, 0.5],
                                                                       [1, 0], [0, 0]]}}})", 2);
  EXPECT_EQ(fill_points("polygon", r.alternative_values("shape"), dp, 2, {}, {}).size(), pts.size());
}

TEST(Geometry, PolygonWallLayersFollowItsEdges) {
  const ParamValues b = shape(l_shape, 2);
  const auto pts = wall_points("polygon", b.alternative_values("shape"), 0.05, 2, 1, {}, {});
  // One layer inside the boundary: the perimeter (4) in units of dp, minus the outer corners counted twice,
  // plus the re-entrant corner's extra particle: 80 - 5 + 1.
  EXPECT_EQ(pts.size(), 76u);
}

TEST(Geometry, PolygonNeedsThreeCornersAnAreaAndA2dDomain) {
  EXPECT_THROW(shape(R"({"shape": {"polygon": {"vertices": [[0, 0], [1, 0]]}}})", 2), InputError);
  const ParamValues flat = shape(R"({"shape": {"polygon": {"vertices": [[0, 0], [1, 0], [2, 0]]}}})", 2);
  EXPECT_THROW(fill_points("polygon", flat.alternative_values("shape"), 0.1, 2, {}, {}), InputError);
  const ParamValues in3d = shape(R"({"shape": {"polygon": {"vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]]}}})", 3);
  EXPECT_THROW(fill_points("polygon", in3d.alternative_values("shape"), 0.1, 3, {}, {}), InputError);
}

// Every point of the lattice over [lo, lo + n dp], tested one by one: what the
// generator's skipping must reproduce exactly.
template <class Keep>
std::vector<Vec3> every_point(const Vec3& lo, const int n[3], const Vec3& s, int dim, Keep keep) {
  std::vector<Vec3> out;
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i) {
        const Vec3 p{lo.x + (i + 0.5) * s.x, lo.y + (j + 0.5) * s.y, dim == 3 ? lo.z + (k + 0.5) * s.z : 0.0};
        if (keep(p)) out.push_back(p);
      }
  return out;
}
template <class Keep>
std::vector<Vec3> every_point(const Vec3& lo, const int n[3], double dp, int dim, Keep keep) {
  return every_point(lo, n, Vec3{dp, dp, dp}, dim, keep);
}

void expect_same_points(const std::vector<Vec3>& got, const std::vector<Vec3>& want) {
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t k = 0; k < got.size(); ++k) ASSERT_LT(norm(got[k] - want[k]), 1e-12) << "point " << k;  // the test sums its corner another way
}

TEST(Geometry, SkippingKeepsEveryPointOfASphereShellAndFill) {
  const ParamValues b = shape(R"({"shape": {"sphere": {"centre": [0.013, -0.2, 0.31], "radius": 0.47}}})");
  const Vec3 c{0.013, -0.2, 0.31};
  const double r = 0.47, dp = 0.02, t = 3 * dp;
  const Vec3 lo = c - Vec3{r, r, r};
  const int n[3] = {48, 48, 48};  // the lattice over the bounding box and one dp beyond, as the generator lays it
  expect_same_points(wall_points("sphere", b.alternative_values("shape"), dp, 3, 3, {}, {}),
                     every_point(lo, n, dp, 3, [&](const Vec3& p) { return norm(p - c) < r && r - norm(p - c) < t; }));
  expect_same_points(fill_points("sphere", b.alternative_values("shape"), dp, 3, {}, {}),
                     every_point(lo, n, dp, 3, [&](const Vec3& p) { return norm(p - c) < r; }));
}

TEST(Geometry, SkippingKeepsEveryPointOfATiltedCylinderShell) {
  const ParamValues b = shape(
      R"({"shape": {"cylinder": {"base": [0.1, 0.2, 0.3], "axis": [1, 2, 2], "radius": 0.2, "height": 0.6}}})");
  const Vec3 base{0.1, 0.2, 0.3}, axis = Vec3{1, 2, 2} / 3.0;
  const double r = 0.2, len = 0.6, dp = 0.025, t = 2 * dp;
  const Vec3 lo = base - Vec3{r + len, r + len, r + len};
  const int n[3] = {65, 65, 65};
  expect_same_points(wall_points("cylinder", b.alternative_values("shape"), dp, 3, 2, {}, {}),
                     every_point(lo, n, dp, 3, [&](const Vec3& p) {
                       const double s = dot(p - base, axis), rho = norm(p - base - axis * s);
                       return s >= 0 && s <= len && rho < r && std::min({s, len - s, r - rho}) < t;
                     }));
}

TEST(Geometry, SkippingKeepsEveryPointOfBoxWallsAndOfAHalfSpace) {
  const ParamValues w = shape(R"({"shape": {"box_walls": {"min": [0, 0, 0], "max": [0.83, 0.5, 0.61], "open": ["+z"]}}})");
  const double dp = 0.05;
  // The box's lattice (16.6, 10 and 12.2 spacings: 17, 10 and 12 particles; dp along z, open at +z) and 3
  // layers beyond its closed faces.
  const Vec3 s{0.83 / 17, 0.5 / 10, dp};
  const int n[3] = {17 + 6, 10 + 6, 12 + 3};
  expect_same_points(wall_points("box_walls", w.alternative_values("shape"), dp, 3, 3, {}, {}),
                     every_point(s * -3.0, n, s, 3, [](const Vec3& p) {
                       return p.x < 0 || p.x > 0.83 || p.y < 0 || p.y > 0.5 || p.z < 0 || p.z > 0.61;
                     }));
  const ParamValues h = shape(R"({"shape": {"half_space": {"point": [0.3, 0.4], "normal": [1, 3]}}})", 2);
  const Vec3 x0{0.3, 0.4, 0.0}, normal = Vec3{1, 3, 0} / std::sqrt(10.0);
  const int m[3] = {41, 31, 1};
  expect_same_points(wall_points("half_space", h.alternative_values("shape"), 0.025, 2, 2, {0, 0, 0}, {1, 0.75, 0}),
                     every_point(Vec3{0, 0, 0}, m, 0.025, 2, [&](const Vec3& p) {
                       const double behind = -dot(p - x0, normal);
                       return behind > 0 && behind < 0.05;
                     }));
}

TEST(Geometry, PlatesOfAChannelWithOpenSidesCostThePlatesAtAnyHeight) {
  // Only the bottom and top plates: 2 layers of 8 each; the 2e13 rows between them hold nothing.
  const ParamValues b = shape(R"({"shape": {"box_walls": {"min": [0, 0], "max": [0.0004, 1e9], "open": ["-x", "+x"]}}})", 2);
  const auto pts = wall_points("box_walls", b.alternative_values("shape"), 5e-5, 2, 2, {}, {});
  EXPECT_EQ(pts.size(), 2u * 2u * 8u);
  const ParamValues c =
      shape(R"({"shape": {"box_walls": {"min": [0, 0, 0], "max": [1, 1, 1e9], "open": ["-x", "+x", "-y", "+y"]}}})");
  EXPECT_EQ(wall_points("box_walls", c.alternative_values("shape"), 0.1, 3, 1, {}, {}).size(), 2u * 10u * 10u);
}

TEST(Geometry, WallsOfALargeTankCostTheirSurfaceNotTheTankVolume) {
  // 20 km by 10 km at dp = 0.05: 8e10 lattice points inside (minutes to test one by one), 1.6e6 wall particles.
  const ParamValues b = shape(R"({"shape": {"box_walls": {"min": [0, 0], "max": [20000, 10000], "open": ["+y"]}}})", 2);
  const auto pts = wall_points("box_walls", b.alternative_values("shape"), 0.05, 2, 2, {}, {});
  EXPECT_EQ(pts.size(), (400000u + 4u) * 2u + 200000u * 2u * 2u);
}

// mDBC ghost nodes mirror each wall particle across the surface point nearest it.
TEST(Geometry, WallSurfacePointsOfATankLieOnItsFacesEdgesAndCorners) {
  const ParamValues b = shape(R"({"shape": {"box_walls": {"min": [0, 0], "max": [0.4, 0.3], "open": ["+y"]}}})", 2);
  const ParamValues& tank = b.alternative_values("shape");
  const auto pts = wall_points("box_walls", tank, 0.02, 2, 3, {}, {});
  const auto surface = wall_surface("box_walls", tank, 2, {}, {});
  int corners = 0;
  for (const Vec3& p : pts) {
    const Vec3 s = surface(p);
    const bool below = p.y < 0.0, left = p.x < 0.0, right = p.x > 0.4;
    EXPECT_DOUBLE_EQ(s.y, below ? 0.0 : p.y);
    EXPECT_DOUBLE_EQ(s.x, left ? 0.0 : right ? 0.4 : p.x);
    if (below && (left || right)) ++corners;  // mirrored through the corner point
  }
  EXPECT_EQ(corners, 2 * 3 * 3);
}

TEST(Geometry, WallSurfacePointsOfSolidsAreTheNearestPointsOfTheirSurfaces) {
  const ParamValues box = shape(R"({"shape": {"box": {"min": [0, 0, 0], "max": [1, 2, 3]}}})");
  const auto on_box = wall_surface("box", box.alternative_values("shape"), 3, {}, {});
  EXPECT_EQ(on_box({0.1, 1.0, 1.5}), (Vec3{0.0, 1.0, 1.5}));
  EXPECT_EQ(on_box({0.5, 1.9, 1.5}), (Vec3{0.5, 2.0, 1.5}));
  EXPECT_EQ(on_box({0.5, 1.0, 0.2}), (Vec3{0.5, 1.0, 0.0}));
  const ParamValues ball = shape(R"({"shape": {"sphere": {"centre": [1, 1, 1], "radius": 0.5}}})");
  const auto on_ball = wall_surface("sphere", ball.alternative_values("shape"), 3, {}, {});
  EXPECT_NEAR(norm(on_ball({1.3, 1.0, 1.0}) - Vec3{1.5, 1.0, 1.0}), 0.0, 1e-15);
  EXPECT_NEAR(norm(on_ball({1.0, 1.0, 0.8}) - Vec3{1.0, 1.0, 0.5}), 0.0, 1e-15);
  const ParamValues half = shape(R"({"shape": {"half_space": {"point": [0, 0, 1], "normal": [0, 0, 2]}}})");
  const auto on_plane = wall_surface("half_space", half.alternative_values("shape"), 3, {0, 0, 0}, {1, 1, 2});
  EXPECT_NEAR(norm(on_plane({0.3, 0.4, 0.9}) - Vec3{0.3, 0.4, 1.0}), 0.0, 1e-15);
  const ParamValues can = shape(R"({"shape": {"cylinder": {"base": [0, 0, 0], "radius": 1, "height": 4}}})");
  const auto on_can = wall_surface("cylinder", can.alternative_values("shape"), 3, {}, {});
  EXPECT_NEAR(norm(on_can({0.9, 0.0, 2.0}) - Vec3{1.0, 0.0, 2.0}), 0.0, 1e-15);
  EXPECT_NEAR(norm(on_can({0.0, 0.2, 0.1}) - Vec3{0.0, 0.2, 0.0}), 0.0, 1e-15);
  EXPECT_NEAR(norm(on_can({0.1, 0.0, 3.8}) - Vec3{0.1, 0.0, 4.0}), 0.0, 1e-15);
}

TEST(Mesh, ObjCubeContainsAndMeasures) {
  const std::string path = std::string(TALUS_BINARY_DIR) + "/tests/cube_test.obj";
  test::write_file(path,
                   "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
                   "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n");
  const TriangleMesh m = load_mesh(path);
  EXPECT_EQ(m.triangles.size(), 12u);
  EXPECT_TRUE(m.contains({0.5, 0.5, 0.5}));
  EXPECT_FALSE(m.contains({1.5, 0.5, 0.5}));
  EXPECT_NEAR(m.distance({0.5, 0.5, 0.2}), 0.2, 1e-12);
  EXPECT_NEAR(dot(m.normal(0), {0, 0, -1}), 1.0, 1e-12);
}

// Walls, fills and the inside test need a closed surface whose normals all point outwards.
TEST(Mesh, OpenFlippedOrInsideOutSurfacesAreRefusedWithTheReason) {
  const std::string corners = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n";
  auto refused = [&](const std::string& name, const std::string& faces, const std::string& words) {
    const std::string path = std::string(TALUS_BINARY_DIR) + "/tests/" + name + ".obj";
    test::write_file(path, corners + faces);
    try {
      load_mesh(path);
      ADD_FAILURE() << name << " was accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(name + ".obj"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
  };
  refused("open_box", "f 1 4 3 2\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n", "not closed");
  refused("flipped_face", "f 1 4 3 2\nf 8 7 6 5\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n", "flipped");
  refused("inside_out", "f 2 3 4 1\nf 8 7 6 5\nf 5 6 2 1\nf 6 7 3 2\nf 7 8 4 3\nf 8 5 1 4\n", "inwards");
}

TEST(Mesh, BadFilesNameTheFileAndLine) {
  const std::string path = std::string(TALUS_BINARY_DIR) + "/tests/bad_test.obj";
  test::write_file(path, "v 0 0 0\nv 1 0 0\nf 1 2 7\n");
  try {
    load_mesh(path);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bad_test.obj:3: face refers to vertex 7"), std::string::npos) << e.what();
  }
  EXPECT_THROW(load_mesh(std::string(TALUS_BINARY_DIR) + "/tests/missing.stl"), InputError);
}

TEST(Motion, PistonAndHingeFollowTheirFormulas) {
  ParamSet body{"body", "b"};
  PrescribedMotion::declare(body);
  const ParamValues v = params_from_json(
      body, R"({"motion": {"sine": {"direction": [2, 0, 0], "amplitude": 0.1, "period": 2}}})");
  const PrescribedMotion piston(v.alternative("motion"), v.alternative_values("motion"));
  EXPECT_NEAR(piston.position({1, 0, 0}, 0.5).x, 1.1, 1e-12);  // quarter period: full stroke
  EXPECT_NEAR(piston.velocity({1, 0, 0}, 0.0).x, 0.1 * std::numbers::pi, 1e-12);

  const ParamValues h = params_from_json(
      body, R"({"motion": {"hinge": {"point": [0, 0, 0], "axis": [0, 1, 0], "amplitude": 0.5, "period": 4}}})");
  const PrescribedMotion flap(h.alternative("motion"), h.alternative_values("motion"));
  const Vec3 top = flap.position({0, 0, 1}, 1.0);  // rotated by 0.5 rad about +y
  EXPECT_NEAR(top.x, std::sin(0.5), 1e-12);
  EXPECT_NEAR(top.z, std::cos(0.5), 1e-12);
}

}  // namespace
}  // namespace talus
