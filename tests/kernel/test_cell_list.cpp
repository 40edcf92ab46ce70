// The cell list against brute force, in 2D and 3D, closed and periodic.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "talus/cell_list.hpp"

namespace talus {
namespace {

struct Case {
  int dim;
  std::array<bool, 3> periodic;
};

class CellListVsBruteForce : public ::testing::TestWithParam<Case> {};

TEST_P(CellListVsBruteForce, FindsExactlyThePairsWithinTheRadius) {
  const auto [dim, periodic] = GetParam();
  const Vec3 lo{-0.3, 0.1, 0.0}, hi{0.7, 0.9, dim == 3 ? 0.8 : 0.0};
  const double radius = 0.13;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec3> pos(dim == 3 ? 1500 : 600);
  for (auto& p : pos)
    p = {lo.x + u(rng) * (hi.x - lo.x), lo.y + u(rng) * (hi.y - lo.y), dim == 3 ? lo.z + u(rng) * (hi.z - lo.z) : 0.0};

  CellList cells;
  cells.configure(dim, lo, hi, radius, periodic);
  cells.build(pos);
  const Vec3 period{hi.x - lo.x, hi.y - lo.y, hi.z - lo.z};
  std::size_t pairs = 0;
  for (std::size_t i = 0; i < pos.size(); ++i) {
    std::vector<std::pair<Index, double>> found;
    cells.for_each_neighbour(pos[i], pos, radius, [&](Index j, const Vec3& dx, double r2) {
      EXPECT_NEAR(norm2(dx), r2, 1e-14);
      found.emplace_back(j, r2);
    });
    std::vector<std::pair<Index, double>> expected;
    for (std::size_t j = 0; j < pos.size(); ++j) {
      Vec3 d = pos[i] - pos[j];
      for (int a = 0; a < dim; ++a)
        if (periodic[a]) d[a] -= period[a] * std::round(d[a] / period[a]);
      if (norm2(d) < radius * radius) expected.emplace_back(static_cast<Index>(j), norm2(d));
    }
    std::sort(found.begin(), found.end());
    std::sort(expected.begin(), expected.end());
    ASSERT_EQ(found.size(), expected.size()) << "particle " << i;
    for (std::size_t k = 0; k < found.size(); ++k) {
      EXPECT_EQ(found[k].first, expected[k].first);
      EXPECT_NEAR(found[k].second, expected[k].second, 1e-12);
    }
    pairs += found.size();
  }
  EXPECT_GT(pairs, pos.size() * 3);  // the test really looks at neighbours
}

INSTANTIATE_TEST_SUITE_P(Layouts, CellListVsBruteForce,
                         ::testing::Values(Case{2, {false, false, false}}, Case{2, {true, false, false}},
                                           Case{2, {true, true, false}}, Case{3, {false, false, false}},
                                           Case{3, {false, true, false}}, Case{3, {true, true, true}}),
                         [](const ::testing::TestParamInfo<Case>& info) {
                           std::string name = std::to_string(info.param.dim) + "d_periodic_";
                           for (int a = 0; a < 3; ++a) name += info.param.periodic[a] ? "xyz"[a] : '_';
                           return name;
                         });

TEST(CellList, OrderIsAPermutationSortedByCell) {
  std::vector<Vec3> pos;
  for (int i = 0; i < 100; ++i) pos.push_back({std::fmod(i * 0.37, 1.0), std::fmod(i * 0.61, 1.0), 0.0});
  CellList cells;
  cells.configure(2, {0, 0, 0}, {1, 1, 0}, 0.25);
  cells.build(pos);
  auto order = std::vector<Index>(cells.order().begin(), cells.order().end());
  std::sort(order.begin(), order.end());
  for (Index i = 0; i < 100; ++i) EXPECT_EQ(order[i], i);
}

// An extent of 2e19 m over 0.1 m cells: coarsened to a grid that fits, not a
// wrapped cell count and writes past the end.
TEST(CellList, HugeExtentIsCoarsenedNotOverflowed) {
  const std::vector<Vec3> pos = {{-1e19, -1e19, -1e19}, {1e19, 1e19, 1e19}, {0, 0, 0}, {0.05, 0, 0}};
  CellList cells;
  cells.configure(3, pos[0], pos[1], 0.1);
  cells.build(pos);
  std::vector<Index> found;
  cells.for_each_neighbour(pos[2], pos, 0.1, [&](Index j, const Vec3&, double) { found.push_back(j); });
  std::sort(found.begin(), found.end());
  EXPECT_EQ(found, (std::vector<Index>{2, 3}));
}

TEST(CellList, RejectsAPeriodicAxisShorterThanThreeCells) {
  CellList cells;
  EXPECT_THROW(cells.configure(2, {0, 0, 0}, {0.5, 1, 0}, 0.2, {true, false, false}), InputError);
}

}  // namespace
}  // namespace talus
