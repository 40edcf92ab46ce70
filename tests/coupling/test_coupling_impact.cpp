// Stability on the hard case (issue 8): block_impact.json at a low
// resolution (dp 0.03) through the impact: the run finishes without a
// non-finite value, no fluid particle ends up inside the block, and the fluid
// mass is conserved (no particle lost or created).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <vector>

#include "coupled_run.hpp"
#include "talus/dda/polyhedron.hpp"

using namespace coupling_test;

namespace {
// The fluid's mass summed in order of size: the same total whatever order the
// store holds the particles in (the host re-sorts them; the fit near the block
// gives them different masses).
double total_mass(const talus::ParticleStore& fluid) {
  const auto m = fluid.scalar("mass");
  std::vector<double> sorted(m.begin(), m.end());
  std::sort(sorted.begin(), sorted.end());
  double sum = 0.0;
  for (double v : sorted) sum += v;
  return sum;
}
}  // namespace

TEST(CouplingImpact, BlockImpactStaysStableAndTight) {
  json scene = read_scene("block_impact.json");
  for (auto& body : scene["bodies"])
    if (body.contains("dp")) body["dp"] = 0.03;
  scene["time"]["end"] = 0.62;  // the block enters the water at about 0.42 s
  scene["outputs"] = json::array();
  CoupledRun run(scene, "impact");
  talus::World& w = run.world();
  const std::size_t k = run.block("block");
  const std::size_t n0 = w.fluid.size();
  const double mass0 = total_mass(w.fluid);
  const talus::Vec3 x0 = w.blocks->position[k];
  ASSERT_EQ(run.run(), 0);
  const auto& b = *w.blocks;
  // It did slide into the water.
  EXPECT_LT(b.position[k].z, 0.3) << "the block should be in the water by the end";
  EXPECT_GT(b.position[k].x - x0.x, 0.3);
  // No fluid particle inside the block.
  std::size_t inside = 0;
  double deepest = 1e300;
  for (const talus::Vec3& x : w.fluid.position()) {
    const double d = talus::dda::plane_distance(b.shape[k], rotate_inverse(b.orientation[k], x - b.position[k]));
    deepest = std::min(deepest, d);
    inside += d < 0.0;
  }
  std::printf("impact: block at (%.3f, %.3f, %.3f), %zu fluid particles, closest to the block %.4f m outside its "
              "faces, %zu inside\n", b.position[k].x, b.position[k].y, b.position[k].z, w.fluid.size(), deepest, inside);
  EXPECT_EQ(inside, 0u);
  // Mass conserved.
  EXPECT_EQ(w.removed, 0u);
  EXPECT_EQ(w.fluid.size(), n0);
  EXPECT_EQ(total_mass(w.fluid), mass0);
}
