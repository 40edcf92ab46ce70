// Fluid that passes a wall is found, put back on the wall surface, counted
// once and warned (dynamic_particles, either method): a particle inside the
// tank's wall slab is a crossing; one in the tank, or one that went over a
// wall's top, is not.
#include <gtest/gtest.h>

#include <string>

#include "sph_world.hpp"
#include "talus/geometry.hpp"

namespace {

using sph_test::SphWorld;
using talus::Vec3;

// A 2D tank [0, 0.4] x [0, 0.3], open at the top, its walls 3 layers (0.06 m) thick,
// with water and one extra fluid particle at `stray`.
std::uint64_t crossings(const Vec3& stray, const std::string& model_json, std::size_t* warnings = nullptr,
                        Vec3* stray_after = nullptr) {
  SphWorld s(2, {-0.1, -0.1, 0}, {0.5, 0.4, 0}, 0.02, 1.5);
  const int water = s.water(20.0);
  s.fluid_box(water, {0, 0, 0}, {0.4, 0.1, 0}, true);
  auto& f = s.world.fluid;
  const std::size_t i = f.append(1);
  f.position()[i] = stray;
  f.scalar("density")[i] = 1000.0;
  f.scalar("mass")[i] = 0.4;
  f.material()[i] = water;
  f.body()[i] = 0;
  s.world.refresh_material_index();
  auto model = std::make_unique<talus::boundary::DynamicParticles>(
      talus::params_from_json(talus::boundary::DynamicParticles::describe(), model_json, 2));
  talus::Body body;
  body.name = "tank";
  body.kind = talus::BodyKind::wall;
  body.dp = 0.02;
  body.material = water;
  body.boundary = model.get();
  body.params = sph_test::body_values(
      R"({"shape": {"box_walls": {"min": [0, 0], "max": [0.4, 0.3], "open": ["+y"]}}, "layers": 3})", 2);
  const int bi = static_cast<int>(s.world.bodies.size());
  s.world.bodies.push_back(body);
  model->setup(s.world, std::span<const int>(&bi, 1));
  s.models.push_back(std::move(model));
  s.make_stage(R"({"viscosity": "artificial", "alpha": 0.01})");
  s.step(1e-5);
  s.step(1e-5);  // found once, counted once
  if (warnings) *warnings = s.world.warnings.all().size();
  const auto ids = f.ids();
  for (std::size_t k = 0; k < f.size(); ++k)
    if (ids[k] == ids.size() - 1 && stray_after) *stray_after = f.position()[k];
  return s.world.wall_crossings;
}

TEST(WallCrossings, AParticleInsideTheWallSlabIsPutBackCountedOnceAndWarned) {
  std::size_t warned = 0;
  Vec3 after;
  EXPECT_EQ(crossings({0.2, -0.03, 0}, "{}", &warned, &after), 1u);  // in the floor
  EXPECT_EQ(warned, 1u);
  EXPECT_NEAR(after.x, 0.2, 1e-6);
  EXPECT_GE(after.y, 0.0) << "on the floor's surface, no longer moving into it";
  EXPECT_LT(after.y, 1e-6);
  EXPECT_EQ(crossings({0.43, 0.2, 0}, R"({"method": "mdbc"})", nullptr, &after), 1u);  // in the right wall
  EXPECT_LE(after.x, 0.4);
  EXPECT_GT(after.x, 0.4 - 1e-6);
}

TEST(WallCrossings, FluidInTheTankOrBeyondTheWallsIsNotACrossing) {
  std::size_t warned = 0;
  EXPECT_EQ(crossings({0.2, 0.2, 0}, "{}", &warned), 0u);  // in the tank, away from the water
  EXPECT_EQ(warned, 0u);
  EXPECT_EQ(crossings({0.43, 0.302, 0}, "{}"), 0u);  // just over the right wall's top, outside its slab
  EXPECT_EQ(crossings({0.462, 0.2, 0}, "{}"), 0u);  // just beyond the wall's 3 layers
}

TEST(WallCrossings, WallRegionOfATankIsTheSlabBehindItsClosedFaces) {
  talus::ParamSet b{"body", "test"};
  talus::declare_shape(b);
  const auto v = talus::params_from_json(
      b, R"({"shape": {"box_walls": {"min": [0, 0, 0], "max": [1, 1, 1], "open": ["+z", "-x"]}}})", 3);
  const auto in_wall = talus::wall_region("box_walls", v.alternative_values("shape"), 0.1, 3, 2, {}, {});
  EXPECT_TRUE(in_wall({0.5, 0.5, -0.05}));   // floor
  EXPECT_TRUE(in_wall({1.15, 0.5, 0.5}));    // +x wall, 2 layers of 0.1
  EXPECT_FALSE(in_wall({1.25, 0.5, 0.5}));   // beyond it
  EXPECT_FALSE(in_wall({-0.05, 0.5, 0.5}));  // the open -x face
  EXPECT_FALSE(in_wall({0.5, 0.5, 1.05}));   // above the open top
  EXPECT_FALSE(in_wall({0.5, 0.5, 0.5}));    // inside the tank
  EXPECT_TRUE(in_wall({1.05, -0.05, -0.05}));  // the edge behind floor and +x wall
}

}  // namespace
