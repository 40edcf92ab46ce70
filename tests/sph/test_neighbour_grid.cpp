// The SPH neighbour grid (sph/neighbour_grid.hpp) against brute force: the
// same neighbour sets and minimum-image offsets in 2D and 3D, with closed and
// periodic axes, points outside the bounds, and clustered points.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "talus/sph/neighbour_grid.hpp"

namespace {

using talus::Index;
using talus::Vec3;

void compare_with_brute_force(int dim, std::array<bool, 3> periodic, bool outside, unsigned seed) {
  const Vec3 lo{-0.3, 0.1, 0.0}, hi{0.9, 0.7, 0.5};
  const double radius = 0.11;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec3> pos(1500);
  for (auto& p : pos) {
    for (int a = 0; a < dim; ++a) {
      const double margin = outside && !periodic[a] ? 0.2 : 0.0;
      p[a] = lo[a] - margin + (hi[a] - lo[a] + 2 * margin) * u(rng);
    }
    if (u(rng) < 0.2) p = pos[0] + Vec3{0.01 * u(rng), 0.01 * u(rng), dim == 3 ? 0.01 * u(rng) : 0.0};  // clusters
  }
  talus::sph::NeighbourGrid grid;
  grid.configure(dim, lo, hi, radius, periodic);
  grid.build(pos);
  auto min_image = [&](Vec3 d) {
    for (int a = 0; a < dim; ++a)
      if (periodic[a]) d[a] -= (hi[a] - lo[a]) * std::round(d[a] / (hi[a] - lo[a]));
    return d;
  };
  std::size_t total = 0;
  for (std::size_t i = 0; i < pos.size(); ++i) {
    std::vector<std::pair<Index, Vec3>> found, expected;
    grid.for_each_neighbour(pos[i], pos, radius, [&](Index j, const Vec3& dx, double r2) {
      found.push_back({j, dx});
      EXPECT_NEAR(r2, talus::norm2(dx), 1e-15);
    });
    for (std::size_t j = 0; j < pos.size(); ++j) {
      const Vec3 d = min_image(pos[i] - pos[j]);
      if (talus::norm2(d) < radius * radius) expected.push_back({static_cast<Index>(j), d});
    }
    auto by_index = [](const auto& a, const auto& b) { return a.first < b.first; };
    std::sort(found.begin(), found.end(), by_index);
    std::sort(expected.begin(), expected.end(), by_index);
    ASSERT_EQ(found.size(), expected.size()) << "particle " << i;
    for (std::size_t k = 0; k < found.size(); ++k) {
      ASSERT_EQ(found[k].first, expected[k].first);
      EXPECT_NEAR(talus::norm(found[k].second - expected[k].second), 0.0, 1e-12);
    }
    total += found.size();
  }
  EXPECT_GT(total, pos.size() * 3);
}

TEST(NeighbourGrid, MatchesBruteForce2D) { compare_with_brute_force(2, {false, false, false}, false, 1); }
TEST(NeighbourGrid, MatchesBruteForce3D) { compare_with_brute_force(3, {false, false, false}, false, 2); }
TEST(NeighbourGrid, PointsOutsideTheBounds) {
  compare_with_brute_force(2, {false, false, false}, true, 3);
  compare_with_brute_force(3, {false, false, false}, true, 4);
}
TEST(NeighbourGrid, PeriodicAxes) {
  compare_with_brute_force(2, {true, false, false}, true, 5);
  compare_with_brute_force(3, {true, true, false}, true, 6);
  compare_with_brute_force(3, {false, false, true}, false, 7);
}

// Wall particles 1e19 m apart (a fuzzed dp) asked for more cells than a
// size_t counts: the product wrapped, the grid was too small and build()
// wrote past it. The grid is coarsened instead, and still finds neighbours.
TEST(NeighbourGrid, HugeExtentIsCoarsenedNotOverflowed) {
  const std::vector<Vec3> pos = {{-1e19, -1e19, -1e19}, {1e19, 1e19, 1e19}, {0, 0, 0}, {0.05, 0, 0}};
  talus::sph::NeighbourGrid grid;
  grid.configure(3, pos[0], pos[1], 0.1);
  grid.build(pos);
  std::vector<Index> found;
  grid.for_each_neighbour(pos[2], pos, 0.1, [&](Index j, const Vec3&, double) { found.push_back(j); });
  std::sort(found.begin(), found.end());
  EXPECT_EQ(found, (std::vector<Index>{2, 3}));
}

TEST(NeighbourGrid, RejectsTooShortPeriodicAxis) {
  talus::sph::NeighbourGrid grid;
  EXPECT_THROW(grid.configure(2, {0, 0, 0}, {0.2, 1, 0}, 0.1, {true, false, false}), talus::InputError);
}

}  // namespace
