// The level grid finds exactly the pairs a brute-force search finds, for
// radii spread over two orders of magnitude, on closed and periodic axes
// (including reaches longer than half the period, where a particle meets
// several images of another).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <tuple>
#include <vector>

#include "level_grid.hpp"

namespace talus::runout {
namespace {

using Pair = std::tuple<Index, Index, long long>;  // i, j, image offset (rounded x 1e6) to tell images apart

struct Cloud {
  std::vector<Vec3> pos;
  std::vector<double> radius;
};

Cloud random_cloud(std::size_t n, Vec3 lo, Vec3 hi, double r0, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> ux(lo.x, hi.x), uy(lo.y, hi.y), ue(0.0, 1.0);
  Cloud c;
  for (std::size_t i = 0; i < n; ++i) {
    c.pos.push_back({ux(rng), uy(rng), 0.0});
    // Mostly r0, a tail up to 100 r0 (a thin front).
    const double e = ue(rng);
    c.radius.push_back(e < 0.8 ? r0 * (0.5 + e) : r0 * std::pow(100.0, (e - 0.8) / 0.2));
  }
  return c;
}

std::vector<Pair> brute_force(const Cloud& c, Vec3 lo, Vec3 hi, std::array<bool, 3> periodic, bool symmetric) {
  std::vector<Pair> out;
  const double L[2] = {hi.x - lo.x, hi.y - lo.y};
  for (std::size_t i = 0; i < c.pos.size(); ++i)
    for (std::size_t j = 0; j < c.pos.size(); ++j) {
      const double reach = symmetric ? std::max(c.radius[i], c.radius[j]) : c.radius[i];
      // Every image within reach (a few periods either way).
      const int kx = periodic[0] ? 5 : 0, ky = periodic[1] ? 5 : 0;
      for (int ix = -kx; ix <= kx; ++ix)
        for (int iy = -ky; iy <= ky; ++iy) {
          const double dx = c.pos[i].x - (c.pos[j].x + ix * L[0]), dy = c.pos[i].y - (c.pos[j].y + iy * L[1]);
          if (dx * dx + dy * dy < reach * reach)
            out.emplace_back(static_cast<Index>(i), static_cast<Index>(j), std::llround(dx * 1e6) * 1000003 + std::llround(dy * 1e6));
        }
    }
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<Pair> query(LevelGrid& grid, const Cloud& c, bool symmetric) {
  grid.build(c.pos, c.radius);
  std::vector<Pair> out;
  for (std::size_t i = 0; i < c.pos.size(); ++i)
    grid.for_each_neighbour(c.pos[i], c.pos, c.radius[i], symmetric, [&](Index j, const Vec3& d, double) {
      const double reach = symmetric ? std::max(c.radius[i], c.radius[j]) : c.radius[i];
      if (d.x * d.x + d.y * d.y < reach * reach)
        out.emplace_back(static_cast<Index>(i), j, std::llround(d.x * 1e6) * 1000003 + std::llround(d.y * 1e6));
    });
  std::sort(out.begin(), out.end());
  return out;
}

class LevelGridMatchesBruteForce : public ::testing::TestWithParam<std::tuple<bool, bool, bool>> {};

TEST_P(LevelGridMatchesBruteForce, SamePairsAndImages) {
  const auto [px, py, symmetric] = GetParam();
  const Vec3 lo{-3.0, 1.0, 0.0}, hi{5.0, 4.0, 0.0};
  const std::array<bool, 3> periodic{px, py, false};
  const double r0 = 0.1;
  const Cloud c = random_cloud(400, lo, hi, r0, 7u + px + 2 * py + 4 * symmetric);
  const auto expected = brute_force(c, lo, hi, periodic, symmetric);
  LevelGrid grid;
  grid.configure(lo, hi, periodic, r0);
  const auto found = query(grid, c, symmetric);
  EXPECT_GT(expected.size(), c.pos.size() * 2);
  // The largest reaches (up to 10 m) exceed both periods (8 m, 3 m): with
  // periodic axes a pair appears once per image within reach.
  EXPECT_EQ(found, expected);
}

INSTANTIATE_TEST_SUITE_P(Axes, LevelGridMatchesBruteForce,
                         ::testing::Combine(::testing::Bool(), ::testing::Bool(), ::testing::Bool()));

TEST(LevelGrid, RebuildsWithMoreLevelsAndFewerParticles) {
  const Vec3 lo{0.0, 0.0, 0.0}, hi{2.0, 2.0, 0.0};
  Cloud c = random_cloud(200, lo, hi, 0.05, 3u);
  for (double& r : c.radius) r = std::min(r, 0.1);
  LevelGrid grid;
  grid.configure(lo, hi, {false, false, false}, 0.05);
  EXPECT_EQ(query(grid, c, true), brute_force(c, lo, hi, {false, false, false}, true));
  // Fewer particles, and one whose radius needs levels the grid has not laid out yet.
  c.pos.resize(50);
  c.radius.resize(50);
  c.radius[0] = 1.5;
  EXPECT_EQ(query(grid, c, true), brute_force(c, lo, hi, {false, false, false}, true));
  EXPECT_EQ(grid.largest_radius(), 1.5);
}

}  // namespace
}  // namespace talus::runout
