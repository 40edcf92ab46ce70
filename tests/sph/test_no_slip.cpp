// The no-slip option of the dynamic boundary particles ("no_slip"): the
// extrapolated wall velocity 2 v_wall - Shepard(v_fluid) enters the laminar
// viscous term only; a prescribed wall motion starts with its velocity; a wall
// moving along a periodic axis stays in the period.
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "newtonian.hpp"
#include "sph_world.hpp"

namespace {

using sph_test::SphWorld;
using talus::Vec3;

// A wall body whose dynamic_particles model gets `model_json` (e.g. {"no_slip": "wall_velocity"}).
talus::boundary::DynamicParticles* wall(SphWorld& s, const std::string& model_json, const std::string& shape_json,
                                        const std::string& extra = "") {
  auto model = std::make_unique<talus::boundary::DynamicParticles>(
      talus::params_from_json(talus::boundary::DynamicParticles::describe(), model_json, s.world.dim));
  talus::Body body;
  body.name = "wall" + std::to_string(s.world.bodies.size());
  body.kind = talus::BodyKind::wall;
  body.dp = s.world.dp;
  body.boundary = model.get();
  body.params = sph_test::body_values("{\"shape\": " + shape_json + extra + "}", s.world.dim);
  const int bi = static_cast<int>(s.world.bodies.size());
  s.world.bodies.push_back(body);
  model->setup(s.world, std::span<const int>(&bi, 1));
  auto* raw = model.get();
  s.models.push_back(std::move(model));
  return raw;
}

void newtonian(SphWorld& s, int material) {
  auto rheo = std::make_unique<talus::rheology::Newtonian>(
      talus::params_from_json(talus::rheology::Newtonian::describe(), R"({"viscosity": 1e-3})"));
  s.world.materials[material].rheology = rheo.get();
  s.models.push_back(std::move(rheo));
}

// Fluid at rho0 moving uniformly at (u, 0) over a floor at rest, no gravity:
// the fluid-fluid viscous and every pressure term vanish, what is left is the
// wall's viscous drag. Returns the accelerations.
std::vector<Vec3> drag(const std::string& model_json, const std::string& stage_json) {
  SphWorld s(2, {0, -0.1, 0}, {0.4, 0.3, 0}, 0.02, 1.5);
  s.world.periodic = {true, false, false};
  s.world.gravity = {};
  const int water = s.water(1.0);
  newtonian(s, water);
  s.fluid_box(water, {0, 0, 0}, {0.4, 0.2, 0}, false, Vec3{0.01, 0, 0});
  wall(s, model_json, R"({"box_walls": {"min": [0, 0], "max": [0.4, 0.3], "open": ["-x", "+x", "+y"]}})");
  auto& stage = s.make_stage(stage_json);
  stage.compute_rates(s.world);
  const auto a = s.world.fluid.vector("acceleration");
  return {a.begin(), a.end()};
}

TEST(NoSlip, ExtrapolatedWallVelocityDoublesTheDragOfAUniformStream) {
  // Mirrored velocity: 2 * 0 - Shepard(u) = -u, so v_i - v_b* = 2u instead of u.
  const auto mirrored = drag(R"({"no_slip": "extrapolated"})", R"({"viscosity": "laminar"})");
  const auto own = drag(R"({"no_slip": "wall_velocity"})", R"({"viscosity": "laminar"})");
  ASSERT_EQ(mirrored.size(), own.size());
  int near_wall = 0;
  for (std::size_t i = 0; i < own.size(); ++i) {
    EXPECT_NEAR(mirrored[i].x, 2.0 * own[i].x, 1e-12 * (1.0 + std::abs(own[i].x)));
    EXPECT_NEAR(mirrored[i].y, 2.0 * own[i].y, 1e-12);
    if (own[i].x < -1e-9) ++near_wall;  // drag opposes the stream
  }
  EXPECT_GT(near_wall, 0);
}

TEST(NoSlip, DefaultIsExtrapolated) {
  const auto by_default = drag("{}", R"({"viscosity": "laminar"})");
  const auto mirrored = drag(R"({"no_slip": "extrapolated"})", R"({"viscosity": "laminar"})");
  for (std::size_t i = 0; i < by_default.size(); ++i) EXPECT_EQ(by_default[i].x, mirrored[i].x);
}

TEST(NoSlip, ArtificialViscosityIgnoresTheOption) {
  // The artificial viscosity acts on the pairs that approach along x; it must not see the mirrored velocity.
  const std::string stage = R"({"viscosity": "artificial", "alpha": 0.1})";
  const auto a = drag(R"({"no_slip": "extrapolated"})", stage);
  const auto b = drag(R"({"no_slip": "wall_velocity"})", stage);
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].x, b[i].x);
    EXPECT_EQ(a[i].y, b[i].y);
  }
}

TEST(NoSlip, MovingLidStartsWithItsVelocityAndStaysInThePeriod) {
  SphWorld s(2, {0, -0.1, 0}, {0.4, 0.3, 0}, 0.02, 1.5);
  s.world.periodic = {true, false, false};
  s.world.gravity = {};
  const int water = s.water(1.0);
  newtonian(s, water);
  s.fluid_box(water, {0, 0, 0}, {0.4, 0.2, 0}, false);
  auto* lid = wall(s, "{}", R"({"box_walls": {"min": [0, 0], "max": [0.4, 0.2], "open": ["-x", "+x", "-y"]}})",
                   R"(, "motion": {"velocity": {"velocity": [0.05, 0]}})");
  s.make_stage(R"({"viscosity": "laminar"})");
  auto v = s.world.boundary.vector("velocity");
  for (std::size_t b = lid->first(); b < lid->first() + lid->count(); ++b) EXPECT_EQ(v[b].x, 0.05);
  lid->begin_step(s.world);
  lid->advance_walls(s.world, 11.0, 1e-3);  // 0.55 m along x: more than one period (0.4 m)
  const auto x = s.world.boundary.position();
  for (std::size_t b = lid->first(); b < lid->first() + lid->count(); ++b) {
    EXPECT_GE(x[b].x, 0.0);
    EXPECT_LT(x[b].x, 0.4);
  }
}

}  // namespace
