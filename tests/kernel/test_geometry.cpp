// Lattice filling of shapes and wall layers.
#include <gtest/gtest.h>

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
