// The example scenes, loaded body by body into a hand-built world (the
// host's scene loader is exercised by `talus run` elsewhere): the block on an
// incline matches the analytic slide, the rock pile settles with its energy
// balanced.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>

#include "dda_test_world.hpp"

using namespace talus;
using talus::dda::test::BlockScene;

namespace {

void load(BlockScene& s, const std::string& file) {
  std::ifstream in(file);
  ASSERT_TRUE(in) << file;
  const auto scene = nlohmann::json::parse(in);
  const auto& g = scene.at("gravity");
  s.world.gravity = {g[0].get<double>(), g[1].get<double>(), g[2].get<double>()};
  for (auto body : scene.at("bodies")) {
    const std::string contact = body.at("contact").dump();
    body.erase("contact");
    s.add_block(body.dump(), contact);
  }
}

}  // namespace

TEST(DdaScenes, BlockOnInclineMatchesTheAnalyticSlide) {
  BlockScene s;
  load(s, TALUS_SHARE_DIR "/scenes/block_on_incline.json");
  s.start();
  const Vec3 x0 = s.blocks().position[1];
  s.run_until(1.0);
  const double d = norm(s.blocks().position[1] - x0);
  EXPECT_NEAR(d / 0.906407, 1.0, 0.01) << d;
}

TEST(DdaScenes, RockPileSettlesWithItsEnergyBalanced) {
  BlockScene s;
  load(s, TALUS_SHARE_DIR "/scenes/rock_pile.json");
  s.start();
  const auto& e = s.blocks().energy;
  const double e0 = e.kinetic + e.potential + e.strain;
  s.run_until(1.5);
  const double balance = e.kinetic + e.potential + e.strain + e.dissipated - e.external_work - e0;
  std::printf("rock pile at 1.5 s: E kin %.3g J, dissipated %.4g J, balance error %.3g J\n", e.kinetic, e.dissipated,
              balance);
  EXPECT_LT(e.kinetic, 1e-3 * e.dissipated);  // settled: kinetic energy ~0
  EXPECT_LT(std::abs(balance), 0.02 * e.dissipated);  // energy balance within 2 %
  for (std::size_t i = 0; i < s.blocks().size(); ++i) {  // no rock escaped or fell through the floor
    if (s.blocks().fixed[i]) continue;
    EXPECT_GT(s.blocks().position[i].z, 0.0) << s.blocks().name[i];
    EXPECT_LT(std::abs(s.blocks().position[i].x), 0.9) << s.blocks().name[i];
    EXPECT_LT(std::abs(s.blocks().position[i].y), 0.9) << s.blocks().name[i];
  }
}
