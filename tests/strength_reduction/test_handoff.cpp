// The pieces of the hand-off: the vertical extent of a posed block, the
// inverse-distance interpolation of the basal shear (seed eq. 30, m = 1), and
// the rasters of a block resting on a fixed one (volume, terrain, shear).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "handoff.hpp"

using namespace talus;
using namespace talus::strength_reduction;

namespace {

// A box about its centre: its corners (the plan bounds) and face planes (what vertical_extent reads).
Polyhedron box(Vec3 half) {
  Polyhedron p;
  for (int axis = 0; axis < 3; ++axis)
    for (double sign : {-1.0, 1.0}) {
      Vec3 n{};
      n[axis] = sign;
      p.normals.push_back(n);
      p.offsets.push_back(half[axis]);
      p.faces.push_back({});
    }
  for (int k = 0; k < 8; ++k) p.vertices.push_back({k & 1 ? half.x : -half.x, k & 2 ? half.y : -half.y, k & 4 ? half.z : -half.z});
  p.radius = norm(half);
  return p;
}

Quaternion about_y(double degrees) {
  const double a = 0.5 * degrees * std::numbers::pi / 180.0;
  return {std::cos(a), 0.0, std::sin(a), 0.0};
}

}  // namespace

TEST(Handoff, VerticalExtentOfATiltedBox) {
  // A 2 x 2 x 1 box tilted 30 degrees about y: over its centre the vertical
  // chord is 1 / cos 30; the line x = 3 misses it.
  const Polyhedron s = box({1.0, 1.0, 0.5});
  const Vec3 x{0.0, 0.0, 5.0};
  double lo = 0.0, hi = 0.0;
  ASSERT_TRUE(vertical_extent(s, x, about_y(30.0), 0.0, 0.0, lo, hi));
  EXPECT_NEAR(hi - lo, 1.0 / std::cos(std::numbers::pi / 6.0), 1e-12);
  EXPECT_NEAR(0.5 * (hi + lo), 5.0, 1e-12);
  EXPECT_FALSE(vertical_extent(s, x, about_y(30.0), 3.0, 0.0, lo, hi));
  EXPECT_FALSE(vertical_extent(s, x, {}, 0.0, 1.5, lo, hi));
}

TEST(Handoff, InverseDistanceKeepsConstantsNodesAndBounds) {
  const std::vector<Vec3> points{{0, 0, 0}, {4, 0, 0}, {0, 3, 0}, {5, 5, 0}};
  const std::vector<double> constant(4, 7.5);
  for (double x : {-2.0, 0.3, 1.7, 6.0})
    EXPECT_NEAR(inverse_distance(points, constant, x, 0.5 * x, -1.0), 7.5, 1e-12);
  const std::vector<double> values{1.0, 2.0, 3.0, 4.0};
  EXPECT_EQ(inverse_distance(points, values, 4.0, 0.0, -1.0), 2.0);  // on a node: its value
  for (double x = -3.0; x < 8.0; x += 0.7) {  // a weighted mean: inside [min, max]
    const double v = inverse_distance(points, values, x, 1.3, -1.0);
    EXPECT_GE(v, 1.0);
    EXPECT_LE(v, 4.0);
  }
  // With m = 1, between two nodes the weights are linear in the position, so
  // a linear field along the segment is met; with three nodes in the plane it
  // is not: f = x at (0, 0), (2, 0), (0, 2) gives 2/3 at (1, 1), not 1.
  const std::vector<Vec3> pair{{0, 0, 0}, {2, 0, 0}};
  const std::vector<double> linear{0.0, 2.0};
  for (double x : {0.25, 0.5, 1.0, 1.7}) EXPECT_NEAR(inverse_distance(pair, linear, x, 0.0, -1.0), x, 1e-12);
  const std::vector<Vec3> triangle{{0, 0, 0}, {2, 0, 0}, {0, 2, 0}};
  EXPECT_NEAR(inverse_distance(triangle, {{0.0, 2.0, 0.0}}, 1.0, 1.0, -1.0), 2.0 / 3.0, 1e-12);
  EXPECT_EQ(inverse_distance({}, {}, 0.0, 0.0, -1.0), -1.0);
}

TEST(Handoff, LinearNodalFunctionsReproduceALinearField) {
  // f = 3 + 2 x - 5 y at scattered points: exact everywhere, where plain
  // inverse distance is not; along a line of points, exact along the line.
  const auto f = [](double x, double y) { return 3.0 + 2.0 * x - 5.0 * y; };
  const std::vector<Vec3> points{{0, 0, 0}, {4, 0, 1}, {0, 3, 2}, {5, 5, 0}, {-2, 1, 0}, {1.5, -2.5, 0}};
  std::vector<double> values;
  for (const Vec3& p : points) values.push_back(f(p.x, p.y));
  const std::vector<Vec3> g = nodal_gradients(points, values);
  double plain_error = 0.0;
  for (double x = -3.0; x < 7.0; x += 0.9)
    for (double y = -3.0; y < 6.0; y += 1.1) {
      EXPECT_NEAR(inverse_distance_linear(points, values, g, x, y, -1.0), f(x, y), 1e-10) << x << ", " << y;
      plain_error = std::max(plain_error, std::abs(inverse_distance(points, values, x, y, -1.0) - f(x, y)));
    }
  EXPECT_GT(plain_error, 1.0);
  const std::vector<Vec3> line{{0, 0, 0}, {1, 1, 0}, {3, 3, 0}};
  const std::vector<double> along{f(0, 0), f(1, 1), f(3, 3)};
  const std::vector<Vec3> gl = nodal_gradients(line, along);
  for (double t : {-1.0, 0.5, 2.0, 4.0}) EXPECT_NEAR(inverse_distance_linear(line, along, gl, t, t, -1.0), f(t, t), 1e-10);
  // One point: its value everywhere; none: nodata.
  const std::vector<Vec3> one{{1, 1, 0}};
  EXPECT_DOUBLE_EQ(inverse_distance_linear(one, {{7.0}}, nodal_gradients(one, {{7.0}}), 5.0, -2.0, -1.0), 7.0);
  EXPECT_EQ(inverse_distance_linear({}, {}, {}, 0.0, 0.0, -1.0), -1.0);
}

TEST(Handoff, RastersOfABlockOnAFixedBase) {
  // A fixed base (top at z = 0) and a released 4 x 2 x 1 block on it, on a
  // 0.5 m grid: terrain 0 under the block, thickness 1 over its footprint,
  // volume conserved, shear from the two slip-surface contacts.
  BlockSet b;
  b.name = {"base", "block"};
  b.shape = {box({5.0, 5.0, 1.0}), box({2.0, 1.0, 0.5})};
  b.volume = {200.0, 8.0};
  b.mass = {4e5, 16000.0};
  const std::vector<Vec3> position{{0, 0, -1}, {0, 0, 0.5}};
  const std::vector<Quaternion> orientation(2);
  const std::vector<std::uint8_t> released{0, 1};
  LimitState limit;
  limit.point = {{-1, 0, 0}, {1, 0, 0}, {0, 0, 1}};
  limit.area = {4.0, 4.0, 4.0};
  limit.shear_force = {4000.0, 8000.0, 1e9};  // 1 and 2 kPa on the slip surface; the third is not on it
  limit.block_a = {0, 0, 1};
  limit.block_b = {1, 1, 1};
  runout::Grid layout;
  layout.cell = 0.5;
  layout.x0 = -4.75;
  layout.y0 = -2.75;
  layout.resize(20, 12, 0.0);
  const Handoff h = build_handoff(b, position, orientation, released, limit, layout, nullptr);
  EXPECT_EQ(h.slip_contacts, 2u);
  EXPECT_NEAR(h.failed_volume, 8.0, 1e-12);
  EXPECT_NEAR(h.raster_volume, 8.0, 1e-9);
  EXPECT_NEAR(h.density, 2000.0, 1e-9);
  EXPECT_NEAR(h.terrain.at(10, 6), 0.0, 1e-12);       // (0.25, 0.25): the base's top
  EXPECT_NEAR(h.thickness.at(10, 6), 1.0, 1e-12);
  EXPECT_EQ(h.thickness.at(0, 0), 0.0);               // (-4.75, -2.75): off the block
  EXPECT_EQ(h.basal_shear.at(0, 0), layout.nodata);   // no released mass there
  // At (0.25, 0.25): 1 kPa at distance d1 from (-1, 0), 2 kPa at d2 from (1, 0).
  const double d1 = std::hypot(1.25, 0.25), d2 = std::hypot(0.75, 0.25);
  EXPECT_NEAR(h.basal_shear.at(10, 6), (1000.0 / d1 + 2000.0 / d2) / (1.0 / d1 + 1.0 / d2), 1e-9);
  // With linear nodal functions the two contacts' line, 1500 + 500 x Pa, is met exactly.
  const Handoff linear = build_handoff(b, position, orientation, released, limit, layout, nullptr,
                                       BasalShear::inverse_distance_linear);
  EXPECT_NEAR(linear.basal_shear.at(10, 6), 1500.0 + 500.0 * 0.25, 1e-9);
  EXPECT_NEAR(linear.basal_shear.at(12, 4), 1500.0 + 500.0 * 1.25, 1e-9);
}

TEST(Handoff, WithADemTheBlocksAreTerrainOnlyUnderTheFailedMass) {
  // A tessellation's frame: a fixed base (top at z = 0) wider than the ground,
  // a fixed wall rising to z = 6 beside it, a released 4 x 2 x 1 block on the
  // base; the DEM lies at z = 0.5. Under the block the terrain is the base's
  // top (the slip surface); over the wall and the bare base it is the DEM.
  BlockSet b;
  b.name = {"base", "wall", "block"};
  b.shape = {box({5.0, 5.0, 1.0}), box({0.5, 5.0, 3.0}), box({2.0, 1.0, 0.5})};
  b.volume = {200.0, 60.0, 8.0};
  b.mass = {4e5, 1.2e5, 16000.0};
  const std::vector<Vec3> position{{0, 0, -1}, {4.25, 0, 3}, {0, 0, 0.5}};
  const std::vector<Quaternion> orientation(3);
  const std::vector<std::uint8_t> released{0, 0, 1};
  LimitState limit;
  runout::Grid layout;
  layout.cell = 0.5;
  layout.x0 = -4.75;
  layout.y0 = -2.75;
  layout.resize(20, 12, 0.0);
  runout::Grid dem = layout;
  std::fill(dem.value.begin(), dem.value.end(), 0.5);
  const Handoff h = build_handoff(b, position, orientation, released, limit, layout, &dem);
  EXPECT_EQ(h.terrain.at(10, 6), 0.0);   // (0.25, 0.25): under the block, the base's top
  EXPECT_EQ(h.terrain.at(18, 6), 0.5);   // (4.25, 0.25): over the wall, the DEM
  EXPECT_EQ(h.terrain.at(2, 6), 0.5);    // (-3.75, 0.25): over the bare base, the DEM
  EXPECT_NEAR(h.raster_volume, 8.0, 1e-9);
  const Handoff alone = build_handoff(b, position, orientation, released, limit, layout, nullptr);
  EXPECT_EQ(alone.terrain.at(18, 6), 6.0);  // without a DEM the blocks are all the terrain there is
  EXPECT_EQ(alone.terrain.at(2, 6), 0.0);
}
