// Coupling adds nothing without water (issue 8, validation): the DDA block on
// a dry 30 degree incline (share/scenes/block_on_incline.json, friction angle
// 20 degrees) runs inside the coupled solver — the cube has block_particles,
// a small pool of water sits in its own tank far away, the dda stage
// sub-cycles inside the SPH step — and must follow the analytic slide
//   d(t) = g (sin 30 - cos 30 tan 20) t^2 / 2
// while the fluid force on it stays exactly zero.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "coupled_run.hpp"

using namespace coupling_test;

TEST(CouplingDrySlide, BlockOnDryInclineFollowsTheAnalyticSlide) {
  json scene = read_scene("block_on_incline.json");
  scene["kernel"] = json::parse(R"({"type": "wendland_c2", "h_over_dp": 1.3})");
  scene["materials"] = json::parse(R"({"water": {"density": 1000, "eos": {"type": "tait", "c0": 10, "gamma": 7}}})");
  for (auto& body : scene["bodies"])
    if (body["name"] == "cube") body["boundary"] = json::parse(R"({"type": "block_particles"})");
  scene["bodies"].push_back(json::parse(R"({"name": "pool", "kind": "fluid", "material": "water", "dp": 0.05,
      "hydrostatic": true, "shape": {"box": {"min": [3.0, -0.9, -2.5], "max": [3.3, -0.6, -2.35]}}})"));
  scene["bodies"].push_back(json::parse(R"({"name": "pool_tank", "kind": "wall", "dp": 0.05,
      "boundary": {"type": "dynamic_particles"},
      "shape": {"box_walls": {"min": [3.0, -0.9, -2.5], "max": [3.3, -0.6, -2.3], "open": ["+z"]}}})"));
  scene["pipeline"] = json::parse(R"([{"stage": "dda", "safety": 0.5, "subcycle": true}, {"stage": "wcsph"}])");
  scene["time"] = json::parse(R"({"end": 0.6})");
  scene["outputs"] = json::array();
  CoupledRun run(scene, "dry_slide");
  talus::World& w = run.world();
  const std::size_t k = run.block("cube");
  const talus::Vec3 x0 = w.blocks->position[k];
  ASSERT_EQ(run.run(), 0);
  const double t = w.time, deg = std::numbers::pi / 180.0;
  const double a = 9.81 * (std::sin(30 * deg) - std::cos(30 * deg) * std::tan(20 * deg));
  const talus::Vec3 along{std::cos(30 * deg), 0.0, -std::sin(30 * deg)};
  const double d = dot(w.blocks->position[k] - x0, along), expected = 0.5 * a * t * t;
  std::printf("dry slide: d(%.3f s) = %.5f m, analytic %.5f m (%+.3f%%)\n", t, d, expected,
              100.0 * (d / expected - 1.0));
  EXPECT_NEAR(d, expected, 0.01 * expected);
  // The only fluid is far away: the coupling's force on the cube is exactly zero.
  EXPECT_EQ(w.blocks->external_force[k].x, 0.0);
  EXPECT_EQ(w.blocks->external_force[k].y, 0.0);
  EXPECT_EQ(w.blocks->external_force[k].z, 0.0);
}
