// Block geometry: exact volume, centroid and inertia against hand values,
// face merging, and the errors for invalid blocks.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>

#include "block_shape.hpp"
#include "dda_test_world.hpp"
#include "talus/dda/polyhedron.hpp"
#include "talus/error.hpp"

using namespace talus;
using namespace talus::dda;

namespace {

BlockGeometry geometry(const std::string& shape_json) {
  const auto p = params_from_json(test::block_body_params(),
                                  R"({"name": "rock", "kind": "block", "density": 1, "shape": )" + shape_json + "}", 3,
                                  "scene.json");
  return block_geometry(p, "rock");
}

std::string error_of(const std::string& shape_json) {
  try {
    geometry(shape_json);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

void expect_inertia(const std::array<double, 9>& I, const std::array<double, 9>& expected, double tol) {
  for (int k = 0; k < 9; ++k) EXPECT_NEAR(I[k], expected[k], tol) << "component " << k;
}

}  // namespace

TEST(DdaGeometry, BoxMatchesHandValues) {
  const auto g = geometry(R"({"box": {"min": [0, 0, 0], "max": [2, 1, 3]}})");
  EXPECT_NEAR(g.props.volume, 6.0, 1e-14);
  EXPECT_NEAR(norm(g.props.centroid - Vec3{1.0, 0.5, 1.5}), 0.0, 1e-14);
  // m (b^2 + c^2) / 12 with m = 6
  expect_inertia(g.props.inertia, {5.0, 0, 0, 0, 6.5, 0, 0, 0, 2.5}, 1e-13);
  EXPECT_EQ(g.shape.vertices.size(), 8u);
  EXPECT_EQ(g.shape.faces.size(), 6u);
  EXPECT_EQ(g.shape.edges.size(), 12u);
  EXPECT_NEAR(g.shape.radius, std::sqrt(1.0 + 0.25 + 2.25), 1e-14);
  for (std::size_t f = 0; f < g.shape.faces.size(); ++f)  // outward: the centroid is behind every face
    EXPECT_LT(-g.shape.offsets[f], 0.0);
}

TEST(DdaGeometry, TetrahedronMatchesHandValues) {
  const auto g = geometry(R"({"tetrahedron": {"vertices": [[0,0,0], [1,0,0], [0,1,0], [0,0,1]]}})");
  EXPECT_NEAR(g.props.volume, 1.0 / 6.0, 1e-15);
  EXPECT_NEAR(norm(g.props.centroid - Vec3{0.25, 0.25, 0.25}), 0.0, 1e-15);
  // About the centroid: int x^2 = 1/60 - V/16 = 1/160, int xy = 1/120 - V/16 = -1/480.
  const double d = 2.0 / 160.0, o = 1.0 / 480.0;
  expect_inertia(g.props.inertia, {d, o, o, o, d, o, o, o, d}, 1e-15);
}

TEST(DdaGeometry, WedgeVolumeAndCentroid) {
  const auto g = geometry(R"({"wedge": {"origin": [1, 2, 3], "length": 3, "height": 1.5, "width": 2}})");
  EXPECT_NEAR(g.props.volume, 3.0 * 1.5 * 2.0 / 2.0, 1e-13);
  EXPECT_NEAR(norm(g.props.centroid - Vec3{1.0 + 1.0, 2.0 + 1.0, 3.0 + 0.5}), 0.0, 1e-13);
  // Triangle x-z legs a=3 (x), b=1.5 (z), extruded w=2 (y), m = 4.5:
  // I_yy = m (a^2 + b^2) / 18, I_xz = +m a b / 36 (product of inertia of a right triangle).
  EXPECT_NEAR(g.props.inertia[4], 4.5 * (9.0 + 2.25) / 18.0, 1e-12);
  EXPECT_NEAR(g.props.inertia[2], 4.5 * 3.0 * 1.5 / 36.0, 1e-12);
  EXPECT_EQ(g.shape.faces.size(), 5u);
}

TEST(DdaGeometry, InertiaIsInvariantUnderRotation) {
  // A rotated box: principal moments stay those of the axis-aligned box.
  const auto g = geometry(test::rotated_box_json({0, 0, 0}, {2, 1, 3}, 37.0, {0.3, 0.2, 0.1}));
  EXPECT_NEAR(g.props.volume, 6.0, 1e-12);
  const auto& I = g.props.inertia;
  EXPECT_NEAR(I[0] + I[4] + I[8], 5.0 + 6.5 + 2.5, 1e-12);
  EXPECT_NEAR(I[4], 6.5, 1e-12);  // the rotation axis keeps its moment
}

TEST(DdaGeometry, CoplanarTrianglesMergeIntoOneFace) {
  // A unit cube given as 12 triangles, as an STL would.
  const auto g = geometry(R"({"polyhedron": {"vertices": [[0,0,0],[1,0,0],[0,1,0],[1,1,0],[0,0,1],[1,0,1],[0,1,1],[1,1,1]],
      "faces": [[0,2,3],[0,3,1],[4,5,7],[4,7,6],[0,1,5],[0,5,4],[2,6,7],[2,7,3],[0,4,6],[0,6,2],[1,3,7],[1,7,5]]}})");
  EXPECT_EQ(g.shape.faces.size(), 6u);
  for (const auto& f : g.shape.faces) EXPECT_EQ(f.size(), 4u);
  EXPECT_EQ(g.shape.edges.size(), 12u);
  EXPECT_NEAR(g.props.volume, 1.0, 1e-14);
  expect_inertia(g.props.inertia, {1.0 / 6, 0, 0, 0, 1.0 / 6, 0, 0, 0, 1.0 / 6}, 1e-14);
}

TEST(DdaGeometry, MeshFileIsWeldedAndMerged) {
  const std::string path = ::testing::TempDir() + "dda_cube.stl";
  {
    std::ofstream out(path);
    const double v[8][3] = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {2, 2, 0}, {0, 0, 2}, {2, 0, 2}, {0, 2, 2}, {2, 2, 2}};
    const int t[12][3] = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                          {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
    out << "solid cube\n";
    for (const auto& tri : t) {
      out << "facet normal 0 0 0\nouter loop\n";
      for (int k : tri) out << "vertex " << v[k][0] << " " << v[k][1] << " " << v[k][2] << "\n";
      out << "endloop\nendfacet\n";
    }
    out << "endsolid cube\n";
  }
  const auto g = geometry(R"({"mesh": {"file": ")" + path + R"(", "scale": 0.5, "offset": [1, 0, 0]}})");
  EXPECT_NEAR(g.props.volume, 1.0, 1e-12);
  EXPECT_NEAR(norm(g.props.centroid - Vec3{1.5, 0.5, 0.5}), 0.0, 1e-12);
  EXPECT_EQ(g.shape.vertices.size(), 8u);
  EXPECT_EQ(g.shape.faces.size(), 6u);
}

TEST(DdaGeometry, InvalidBlocksNameTheBlockAndTheProblem) {
  const std::string cube_v = R"("vertices": [[0,0,0],[1,0,0],[0,1,0],[1,1,0],[0,0,1],[1,0,1],[0,1,1],[1,1,1]])";
  // Open: the top face is missing.
  std::string e = error_of(R"({"polyhedron": {)" + cube_v +
                           R"(, "faces": [[0,2,3,1],[0,1,5,4],[2,6,7,3],[0,4,6,2],[1,3,7,5]]}})");
  EXPECT_NE(e.find("block 'rock'"), std::string::npos) << e;
  EXPECT_NE(e.find("not closed"), std::string::npos) << e;
  EXPECT_NE(e.find("scene.json"), std::string::npos) << e;
  EXPECT_NE(e.find("/shape"), std::string::npos) << e;
  // Every face clockwise: inverted.
  e = error_of(R"({"polyhedron": {)" + cube_v +
               R"(, "faces": [[1,3,2,0],[6,7,5,4],[4,5,1,0],[3,7,6,2],[2,6,4,0],[5,7,3,1]]}})");
  EXPECT_NE(e.find("inverted"), std::string::npos) << e;
  // One face flipped: inconsistent orientation.
  e = error_of(R"({"polyhedron": {)" + cube_v +
               R"(, "faces": [[0,2,3,1],[6,7,5,4],[0,1,5,4],[2,6,7,3],[0,4,6,2],[1,3,7,5]]}})");
  EXPECT_NE(e.find("inverted face"), std::string::npos) << e;
  // Non-convex: the top centre pushed down (a dimple), faces as a fan.
  e = error_of(R"({"polyhedron": {"vertices": [[0,0,0],[1,0,0],[0,1,0],[1,1,0],[0,0,1],[1,0,1],[0,1,1],[1,1,1],[0.5,0.5,0.5]],
      "faces": [[0,2,3,1],[0,1,5,4],[2,6,7,3],[0,4,6,2],[1,3,7,5],[4,5,8],[5,7,8],[7,6,8],[6,4,8]]}})");
  EXPECT_NE(e.find("not convex"), std::string::npos) << e;
  // Zero volume: a flat tetrahedron.
  e = error_of(R"({"tetrahedron": {"vertices": [[0,0,0], [1,0,0], [0,1,0], [1,1,0]]}})");
  EXPECT_NE(e.find("zero volume"), std::string::npos) << e;
  // Non-planar face: one corner of the top lifted.
  e = error_of(R"({"polyhedron": {"vertices": [[0,0,0],[1,0,0],[0,1,0],[1,1,0],[0,0,1],[1,0,1],[0,1,1],[1,1,1.2]],
      "faces": [[0,2,3,1],[4,5,7,6],[0,1,5,4],[2,6,7,3],[0,4,6,2],[1,3,7,5]]}})");
  EXPECT_NE(e.find("not planar"), std::string::npos) << e;
  // Index out of range.
  e = error_of(R"({"polyhedron": {)" + cube_v +
               R"(, "faces": [[0,2,3,1],[4,5,7,9],[0,1,5,4],[2,6,7,3],[0,4,6,2],[1,3,7,5]]}})");
  EXPECT_NE(e.find("names vertex 9"), std::string::npos) << e;
  // A sphere is no block.
  e = error_of(R"({"sphere": {"centre": [0,0,0], "radius": 1}})");
  EXPECT_NE(e.find("convex polyhedron"), std::string::npos) << e;
}

TEST(DdaGeometry, RandomTetrahedraMatchTheDeterminant) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<Vec3> corners(4);
    for (auto& c : corners) c = {u(rng), u(rng), u(rng)};
    std::vector<Vec3> v;
    std::vector<std::vector<int>> f;
    tetrahedron_polyhedron(corners, v, f);
    Polyhedron poly;
    MassProperties mp;
    const std::string problem = make_convex_polyhedron(v, f, poly, mp);
    if (!problem.empty()) continue;
    const double expected =
        std::abs(dot(corners[1] - corners[0], cross(corners[2] - corners[0], corners[3] - corners[0]))) / 6.0;
    EXPECT_NEAR(mp.volume, expected, 1e-12);
    const Vec3 c = 0.25 * (corners[0] + corners[1] + corners[2] + corners[3]);
    EXPECT_NEAR(norm(mp.centroid - c), 0.0, 1e-12);
    // Inside test: centroid is behind every face plane.
    EXPECT_LT(plane_distance(poly, Vec3{}), 0.0);
  }
}
