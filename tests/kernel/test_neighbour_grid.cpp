// The neighbour grid against brute force: the same neighbours and image
// offsets in 2D and 3D, on closed and periodic axes (including periods
// shorter than two reaches, where a point meets several images of another),
// for points outside the bounds and clustered points, with one radius and
// with per-point radii spread over two orders of magnitude.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <tuple>
#include <vector>

#include "talus/neighbour_grid.hpp"

namespace talus {
namespace {

// i, j and the image's offset x 1e6 (tells images apart).
using Found = std::tuple<Index, Index, long long, long long, long long>;

Found found(std::size_t i, Index j, const Vec3& d) {
  return {static_cast<Index>(i), j, std::llround(d.x * 1e6), std::llround(d.y * 1e6), std::llround(d.z * 1e6)};
}

struct Cloud {
  int dim = 3;
  Vec3 lo, hi;
  std::array<bool, 3> periodic{};
  std::vector<Vec3> pos;
  std::vector<double> radius;
};

// Points in [lo, hi] (with a margin beyond closed axes if `outside`), a
// fifth of them clustered; in 2D the z coordinate is noise the search must ignore.
Cloud random_cloud(int dim, Vec3 lo, Vec3 hi, std::array<bool, 3> periodic, bool outside, std::size_t n,
                   unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Cloud c{dim, lo, hi, periodic, {}, {}};
  for (std::size_t i = 0; i < n; ++i) {
    Vec3 p{0.0, 0.0, u(rng)};
    for (int a = 0; a < dim; ++a) {
      const double margin = outside && !periodic[a] ? 0.2 : 0.0;
      p[a] = lo[a] - margin + (hi[a] - lo[a] + 2 * margin) * u(rng);
    }
    if (i > 0 && u(rng) < 0.2)
      for (int a = 0; a < dim; ++a) p[a] = c.pos[0][a] + 0.01 * u(rng);
    c.pos.push_back(p);
  }
  return c;
}

// Radii mostly near r0, with a tail up to 100 r0 (a thin run-out front).
void spread_radii(Cloud& c, double r0, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  c.radius.clear();
  for (std::size_t i = 0; i < c.pos.size(); ++i) {
    const double e = u(rng);
    c.radius.push_back(e < 0.8 ? r0 * (0.5 + e) : r0 * std::pow(100.0, (e - 0.8) / 0.2));
  }
}

// Every image of every j within reach(i, j) (at most `largest`) of i.
template <class Reach>
std::vector<Found> brute_force(const Cloud& c, double largest, Reach&& reach) {
  std::vector<Found> out;
  std::array<int, 3> images{};
  for (int a = 0; a < c.dim; ++a)
    if (c.periodic[a]) images[a] = static_cast<int>(std::ceil(largest / (c.hi[a] - c.lo[a]))) + 1;
  for (std::size_t i = 0; i < c.pos.size(); ++i)
    for (std::size_t j = 0; j < c.pos.size(); ++j) {
      const double r = reach(i, j);
      for (int ix = -images[0]; ix <= images[0]; ++ix)
        for (int iy = -images[1]; iy <= images[1]; ++iy)
          for (int iz = -images[2]; iz <= images[2]; ++iz) {
            Vec3 d = c.pos[i] - c.pos[j];
            if (c.dim < 3) d.z = 0.0;
            d -= Vec3{ix * (c.hi.x - c.lo.x), iy * (c.hi.y - c.lo.y), iz * (c.hi.z - c.lo.z)};
            if (norm2(d) < r * r) out.push_back(found(i, static_cast<Index>(j), d));
          }
    }
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<Found> one_radius(const Cloud& c, double radius) {
  NeighbourGrid grid;
  grid.configure(c.dim, c.lo, c.hi, radius, c.periodic);
  grid.build(c.pos);
  std::vector<Found> out;
  for (std::size_t i = 0; i < c.pos.size(); ++i)
    grid.for_each_neighbour(c.pos[i], radius, [&](Index j, const Vec3& dx, double r2) {
      EXPECT_NEAR(r2, norm2(dx), 1e-15);
      if (c.dim < 3) EXPECT_EQ(dx.z, 0.0);
      out.push_back(found(i, j, dx));
    });
  std::sort(out.begin(), out.end());
  return out;
}

// The later-neighbour query from every slot, each pair found entered from
// both sides: every pair of distinct points (and image) exactly once.
std::vector<Found> later_pairs_both_ways(const Cloud& c, double radius) {
  NeighbourGrid grid;
  grid.configure(c.dim, c.lo, c.hi, radius, c.periodic);
  grid.build(c.pos);
  std::vector<Found> out;
  const auto order = grid.order();
  for (std::size_t s = 0; s < order.size(); ++s) {
    const Index i = order[s];
    grid.for_each_later_neighbour(s, radius, [&](Index j, const Vec3& dx, double r2) {
      EXPECT_NEAR(r2, norm2(dx), 1e-15);
      out.push_back(found(i, j, dx));
      out.push_back(found(j, i, -dx));
    });
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<Found> without_self(std::vector<Found> pairs) {
  std::erase_if(pairs, [](const Found& f) { return std::get<0>(f) == std::get<1>(f); });
  return pairs;
}

// Gather: reach = own radius. Candidates: the pairs with r < max(R_i, R_j), kept by the caller.
std::vector<Found> own_radii(NeighbourGrid& grid, const Cloud& c, bool candidates) {
  grid.build(c.pos, c.radius);
  std::vector<Found> out;
  for (std::size_t i = 0; i < c.pos.size(); ++i) {
    auto keep = [&](Index j, const Vec3& d, double r2) {
      const double reach = candidates ? std::max(c.radius[i], c.radius[j]) : c.radius[i];
      if (r2 < reach * reach) out.push_back(found(i, j, d));
    };
    if (candidates)
      grid.for_each_candidate_pair(c.pos[i], c.radius[i], keep);
    else
      grid.for_each_neighbour(c.pos[i], c.radius[i], keep);
  }
  std::sort(out.begin(), out.end());
  return out;
}

struct Layout {
  int dim;
  std::array<bool, 3> periodic;
  bool outside;
};

class OneRadius : public ::testing::TestWithParam<Layout> {};

TEST_P(OneRadius, FindsExactlyTheNeighboursWithinTheRadius) {
  const auto [dim, periodic, outside] = GetParam();
  const double radius = 0.11;
  const Cloud c = random_cloud(dim, {-0.3, 0.1, 0.0}, {0.9, 0.7, 0.5}, periodic, outside, 1200,
                               3u + dim + 2 * periodic[0] + 4 * periodic[1] + 8 * periodic[2] + 16 * outside);
  const auto expected = brute_force(c, radius, [&](std::size_t, std::size_t) { return radius; });
  EXPECT_GT(expected.size(), c.pos.size() * 3);  // the test really looks at neighbours
  EXPECT_EQ(one_radius(c, radius), expected);
}

TEST_P(OneRadius, LaterNeighboursGiveEveryPairOnce) {
  const auto [dim, periodic, outside] = GetParam();
  const double radius = 0.11;
  const Cloud c = random_cloud(dim, {-0.3, 0.1, 0.0}, {0.9, 0.7, 0.5}, periodic, outside, 1200,
                               5u + dim + 2 * periodic[0] + 4 * periodic[1] + 8 * periodic[2] + 16 * outside);
  const auto expected = without_self(brute_force(c, radius, [&](std::size_t, std::size_t) { return radius; }));
  EXPECT_GT(expected.size(), c.pos.size() * 3);
  EXPECT_EQ(later_pairs_both_ways(c, radius), expected);
}

// A pass reads the hits a chunk at a time as its lanes: full chunks while
// more follow, the rest in one last chunk, none left behind, and as many as
// the query reports one by one.
TEST_P(OneRadius, ChunksAreFullButTheLast) {
  const auto [dim, periodic, outside] = GetParam();
  const double radius = 0.11;
  const Cloud c = random_cloud(dim, {-0.3, 0.1, 0.0}, {0.9, 0.7, 0.5}, periodic, outside, 1200,
                               7u + dim + 2 * periodic[0] + 4 * periodic[1] + 8 * periodic[2] + 16 * outside);
  NeighbourGrid grid;
  grid.configure(c.dim, c.lo, c.hi, radius, c.periodic);
  grid.build(c.pos);
  std::size_t carried = 0;
  for (std::size_t s = 0; s < c.pos.size(); ++s)
    for (const bool later : {false, true}) {
      std::vector<int> sizes;
      NeighbourHits hits;
      auto chunk = [&](const NeighbourHits& h) { sizes.push_back(h.count); };
      std::size_t one_by_one = 0;
      auto count = [&](Index, const Vec3&, double) { ++one_by_one; };
      if (later) {
        grid.later_neighbour_chunks(s, radius, hits, chunk);
        grid.for_each_later_neighbour(s, radius, count);
      } else {
        const Vec3& x = c.pos[grid.order()[s]];
        grid.neighbour_chunks(x, radius, hits, chunk);
        grid.for_each_neighbour(x, radius, count);
      }
      EXPECT_EQ(hits.count, 0);
      std::size_t total = 0;
      for (std::size_t k = 0; k < sizes.size(); ++k) {
        if (k + 1 < sizes.size()) EXPECT_EQ(sizes[k], NeighbourHits::size);
        EXPECT_GE(sizes[k], 1);
        EXPECT_LE(sizes[k], NeighbourHits::size);
        total += static_cast<std::size_t>(sizes[k]);
      }
      EXPECT_EQ(total, one_by_one);
      if (sizes.size() > 1) ++carried;
    }
  EXPECT_GT(carried, 100u);  // the clustered fifth has more hits than a chunk holds
}

// The write blocks: every sorted slot in exactly one block, and no point
// written (as i or as a later neighbour j) from two blocks of one colour.
// Returns the number of blocks that hold a point.
std::size_t expect_write_blocks_disjoint(const Cloud& c, double radius) {
  NeighbourGrid grid;
  grid.configure(c.dim, c.lo, c.hi, radius, c.periodic);
  grid.build(c.pos);
  const auto order = grid.order();
  std::vector<int> times_run(order.size(), 0);
  std::size_t filled = 0, clashes = 0;
  for (int colour = 0; colour < grid.write_colours(); ++colour) {
    std::vector<long long> writer(c.pos.size(), -1);
    for (std::size_t k = 0; k < grid.write_blocks(colour); ++k) {
      auto claim = [&](Index p) {
        if (writer[p] >= 0 && writer[p] != static_cast<long long>(k)) ++clashes;
        writer[p] = static_cast<long long>(k);
      };
      std::size_t last_end = 0;
      bool any = false;
      grid.for_each_write_block_run(colour, k, [&](std::size_t begin, std::size_t end) {
        EXPECT_LT(begin, end);
        EXPECT_TRUE(!any || begin > last_end) << "runs are separate and in slot order";
        any = true;
        last_end = end;
        for (std::size_t s = begin; s < end; ++s) {
          ++times_run[s];
          claim(order[s]);
          grid.for_each_later_neighbour(s, radius, [&](Index j, const Vec3&, double) { claim(j); });
        }
      });
      filled += any ? 1 : 0;
    }
  }
  EXPECT_EQ(clashes, 0u);
  EXPECT_EQ(std::count(times_run.begin(), times_run.end(), 1), static_cast<long>(order.size()));
  return filled;
}

TEST_P(OneRadius, WriteBlocksOfAColourShareNoPoint) {
  const auto [dim, periodic, outside] = GetParam();
  const Cloud c = random_cloud(dim, {-0.3, 0.1, 0.0}, {0.9, 0.7, 0.5}, periodic, outside, 1200,
                               9u + dim + 2 * periodic[0] + 4 * periodic[1] + 8 * periodic[2] + 16 * outside);
  // Cells of 0.03 m, 20 along y (x 16 along z): several blocks of each colour.
  EXPECT_GT(expect_write_blocks_disjoint(c, 0.06), dim == 3 ? 18u : 6u);
}

INSTANTIATE_TEST_SUITE_P(Layouts, OneRadius,
                         ::testing::Values(Layout{2, {false, false, false}, false},
                                           Layout{2, {false, false, false}, true}, Layout{2, {true, false, false}, true},
                                           Layout{2, {true, true, false}, false}, Layout{3, {false, false, false}, false},
                                           Layout{3, {false, false, false}, true}, Layout{3, {false, true, false}, false},
                                           Layout{3, {true, true, false}, true}, Layout{3, {true, true, true}, false}));

// A period of 1.5 radii: a point meets up to two images of another along it.
TEST(NeighbourGrid, ReportsEveryImageOnAPeriodShorterThanTwoRadii) {
  const Cloud c = random_cloud(2, {0.0, 0.0, 0.0}, {0.15, 1.0, 0.0}, {true, false, false}, false, 300, 11u);
  const auto expected = brute_force(c, 0.1, [](std::size_t, std::size_t) { return 0.1; });
  EXPECT_EQ(one_radius(c, 0.1), expected);
  EXPECT_EQ(later_pairs_both_ways(c, 0.1), without_self(expected));
  EXPECT_GT(expect_write_blocks_disjoint(c, 0.1), 0u);
}

// Periods of 4 to 9 blocks: more than three blocks along a periodic axis
// must come in a multiple of three, or the first and last of a colour meet.
TEST(NeighbourGrid, WriteBlocksOnShortPeriodsShareNoPoint) {
  for (int cells = 8; cells <= 19; ++cells) {
    const double period = cells * 0.05 + 0.01;
    const Cloud c = random_cloud(2, {0.0, 0.0, 0.0}, {period, period, 0.0}, {true, true, false}, false, 600,
                                 static_cast<unsigned>(cells));
    SCOPED_TRACE(cells);
    expect_write_blocks_disjoint(c, 0.1);
  }
}

class OwnRadii : public ::testing::TestWithParam<std::tuple<bool, bool, bool>> {};

// The largest reaches (10 m) exceed both periods (8 m, 3 m): with periodic
// axes a pair appears once per image within reach.
TEST_P(OwnRadii, SamePairsAndImagesAsBruteForce) {
  const auto [px, py, candidates] = GetParam();
  Cloud c = random_cloud(2, {-3.0, 1.0, 0.0}, {5.0, 4.0, 0.0}, {px, py, false}, false, 400, 7u + px + 2 * py);
  spread_radii(c, 0.1, 5u + 4 * candidates);
  const double largest = *std::max_element(c.radius.begin(), c.radius.end());
  const auto expected = brute_force(c, largest, [&](std::size_t i, std::size_t j) {
    return candidates ? std::max(c.radius[i], c.radius[j]) : c.radius[i];
  });
  EXPECT_GT(expected.size(), c.pos.size() * 2);
  NeighbourGrid grid;
  grid.configure(2, c.lo, c.hi, 0.1, c.periodic);
  EXPECT_EQ(own_radii(grid, c, candidates), expected);
}

INSTANTIATE_TEST_SUITE_P(Axes, OwnRadii, ::testing::Combine(::testing::Bool(), ::testing::Bool(), ::testing::Bool()));

TEST(NeighbourGrid, OwnRadiiIn3D) {
  Cloud c = random_cloud(3, {0.0, 0.0, 0.0}, {1.0, 0.8, 0.6}, {false, true, false}, true, 500, 13u);
  spread_radii(c, 0.04, 17u);
  for (double& r : c.radius) r = std::min(r, 0.5);
  NeighbourGrid grid;
  grid.configure(3, c.lo, c.hi, 0.04, c.periodic);
  EXPECT_EQ(own_radii(grid, c, false), brute_force(c, 0.5, [&](std::size_t i, std::size_t) { return c.radius[i]; }));
}

TEST(NeighbourGrid, RebuildsWithMoreLevelsAndFewerPoints) {
  Cloud c = random_cloud(2, {0.0, 0.0, 0.0}, {2.0, 2.0, 0.0}, {}, false, 200, 3u);
  spread_radii(c, 0.05, 3u);
  for (double& r : c.radius) r = std::min(r, 0.1);
  auto symmetric = [&](std::size_t i, std::size_t j) { return std::max(c.radius[i], c.radius[j]); };
  NeighbourGrid grid;
  grid.configure(2, c.lo, c.hi, 0.05);
  EXPECT_EQ(own_radii(grid, c, true), brute_force(c, 1.5, symmetric));
  // Fewer points, and one whose radius needs levels the grid has not laid out yet.
  c.pos.resize(50);
  c.radius.resize(50);
  c.radius[0] = 1.5;
  EXPECT_EQ(own_radii(grid, c, true), brute_force(c, 1.5, symmetric));
  EXPECT_EQ(grid.largest_radius(), 1.5);
  // Back to one radius: the levels laid out stay, empty, and are not searched.
  grid.build(c.pos);
  EXPECT_EQ(grid.largest_radius(), 0.05);
}

// A sparse set (a thin wall along two faces of a large box and a few points
// beyond the bounds) queried from a lattice through the whole box: queries in
// empty blocks find nothing, queries next to a filled block miss nothing.
TEST(NeighbourGrid, QueriesFromEmptyRegionsOfASparseGrid) {
  for (int dim : {2, 3}) {
    std::vector<Vec3> pos;
    for (int i = 0; i < 60; ++i) {
      pos.push_back({0.017 * i, 0.0, dim == 3 ? 0.3 : 0.0});  // along the floor
      pos.push_back({0.0, 0.013 * i, dim == 3 ? 0.011 * i : 0.0});  // up a side
    }
    pos.push_back({1.3, 1.25, dim == 3 ? 1.1 : 0.0});  // outside the bounds, in the edge cells
    const double radius = 0.05;
    NeighbourGrid grid;
    grid.configure(dim, {0, 0, 0}, {1, 1, 1}, radius);
    grid.build(pos);
    int queries_with_hits = 0;
    for (double qz = -0.05; qz <= (dim == 3 ? 1.2 : -0.05); qz += 0.037)
      for (double qy = -0.05; qy <= 1.3; qy += 0.021)
        for (double qx = -0.05; qx <= 1.35; qx += 0.019) {
          const Vec3 q{qx, qy, dim == 3 ? qz : 0.0};
          std::vector<Index> want, got;
          for (std::size_t j = 0; j < pos.size(); ++j)
            if (norm2(q - pos[j]) < radius * radius) want.push_back(static_cast<Index>(j));
          grid.for_each_neighbour(q, radius, [&](Index j, const Vec3&, double) { got.push_back(j); });
          std::sort(got.begin(), got.end());
          ASSERT_EQ(got, want) << dim << "D query at " << qx << ", " << qy << ", " << qz;
          queries_with_hits += want.empty() ? 0 : 1;
        }
    EXPECT_GT(queries_with_hits, 50) << dim << "D";
  }
}

// A row of cells is skipped when its cells lie beyond the reach across it:
// a point at the near corner of a row one and two cells off in y and z, just
// inside the reach (1e-10 of r^2), is still found, from above and below.
TEST(NeighbourGrid, FindsPointsAtTheNearCornerOfARowJustWithinReach) {
  const double radius = 0.1, cell = 0.05;  // 20 cells an axis on the unit box
  NeighbourGrid grid;
  grid.configure(3, {0, 0, 0}, {1, 1, 1}, radius);
  std::vector<Vec3> queries, pos;
  for (int sy : {-1, 1})
    for (int sz : {-1, 1})
      for (double angle : {0.3, 0.785, 1.2}) {
        const double a = radius * std::sqrt(1.0 - 1e-10) * std::cos(angle);
        const double b = radius * std::sqrt(1.0 - 1e-10) * std::sin(angle);
        // The near edges of the row, on cell boundaries: y = 10 cells, z = 9 cells.
        const double ey = 10 * cell, ez = 9 * cell;
        queries.push_back({0.5, ey - sy * a, ez - sz * b});
        pos.push_back({0.5, ey + sy * 1e-12, ez + sz * 1e-12});  // just inside the row's cells
      }
  grid.build(pos);
  for (std::size_t q = 0; q < queries.size(); ++q) {
    bool found = false;
    grid.for_each_neighbour(queries[q], radius, [&](Index j, const Vec3&, double) { found = found || j == q; });
    ASSERT_LT(norm2(queries[q] - pos[q]), radius * radius) << q;
    EXPECT_TRUE(found) << "query " << q;
  }
}

TEST(NeighbourGrid, RefusesARadiusBeyondTheLastLevel) {
  NeighbourGrid grid;
  grid.configure(2, {0, 0, 0}, {1, 1, 0}, 0.1);
  const std::vector<Vec3> pos{{0.5, 0.5, 0.0}};
  const std::vector<double> radius{0.1 * std::ldexp(1.0, NeighbourGrid::max_levels + 1)};
  EXPECT_THROW(grid.build(pos, radius), RunError);
}

TEST(NeighbourGrid, OrderIsAPermutation) {
  std::vector<Vec3> pos;
  for (int i = 0; i < 100; ++i) pos.push_back({std::fmod(i * 0.37, 1.0), std::fmod(i * 0.61, 1.0), 0.0});
  NeighbourGrid grid;
  grid.configure(2, {0, 0, 0}, {1, 1, 0}, 0.25);
  grid.build(pos);
  auto order = std::vector<Index>(grid.order().begin(), grid.order().end());
  std::sort(order.begin(), order.end());
  for (Index i = 0; i < 100; ++i) EXPECT_EQ(order[i], i);
}

// A grid of some rows of a store (one block's particles among others) finds
// exactly the listed points within the radius, reported by their row.
TEST(NeighbourGrid, SubsetOfRowsFindsOnlyThoseRows) {
  std::vector<Vec3> pos;
  for (int i = 0; i < 200; ++i) pos.push_back({std::fmod(i * 0.37, 1.0), std::fmod(i * 0.61, 1.0), 0.0});
  std::vector<Index> rows;
  for (Index i = 0; i < 200; i += 3) rows.push_back(i);
  NeighbourGrid grid;
  const double radius = 0.15;
  grid.configure(2, {0, 0, 0}, {1, 1, 0}, radius);
  grid.build(pos, std::span<const Index>(rows));
  const Vec3 at{0.4, 0.55, 0.0};
  std::vector<Index> found;
  grid.for_each_neighbour(at, radius, [&](Index j, const Vec3&, double) { found.push_back(j); });
  std::vector<Index> expected;
  for (const Index i : rows)
    if (norm2(pos[i] - at) < radius * radius) expected.push_back(i);
  std::sort(found.begin(), found.end());
  ASSERT_GT(expected.size(), 2u);
  EXPECT_EQ(found, expected);
}

// A grid holds cell starts only for the planes along z its points occupy.
// One grid, rebuilt on a slab high in the box, on one low down, then on
// points everywhere (closed and periodic z), finds what brute force finds
// from its points and from queries through the whole box, above and below
// the slab; its later-neighbour pairs and write blocks cover every pair once.
TEST(NeighbourGrid, HoldsOnlyThePlanesItsPointsOccupy) {
  const double radius = 0.08;
  for (const bool periodic_z : {false, true}) {
    NeighbourGrid grid;
    grid.configure(3, {0, 0, 0}, {1, 1, 1}, radius, {false, false, periodic_z});
    unsigned seed = 40u + periodic_z;
    for (const auto& [z0, z1] : {std::pair{0.6, 0.7}, std::pair{0.0, 0.1}, std::pair{0.0, 1.0}}) {
      Cloud c = random_cloud(3, {0, 0, z0}, {1, 1, z1}, {}, false, 500, ++seed);
      c.lo = {0, 0, 0};
      c.hi = {1, 1, 1};  // the period along z is the box's
      c.periodic = {false, false, periodic_z};
      grid.build(c.pos);
      auto within = [&](std::size_t, std::size_t) { return radius; };
      std::vector<Found> got;
      for (std::size_t i = 0; i < c.pos.size(); ++i)
        grid.for_each_neighbour(c.pos[i], radius,
                                [&](Index j, const Vec3& dx, double) { got.push_back(found(i, j, dx)); });
      std::sort(got.begin(), got.end());
      EXPECT_EQ(got, brute_force(c, radius, within)) << "slab " << z0 << " .. " << z1;
      std::vector<Found> later;
      const auto order = grid.order();
      for (std::size_t s = 0; s < order.size(); ++s)
        grid.for_each_later_neighbour(s, radius, [&](Index j, const Vec3& dx, double) {
          later.push_back(found(order[s], j, dx));
          later.push_back(found(j, order[s], -dx));
        });
      std::sort(later.begin(), later.end());
      EXPECT_EQ(later, without_self(brute_force(c, radius, within))) << "slab " << z0 << " .. " << z1;
      for (double qz = -0.05; qz <= 1.05; qz += 0.0437) {  // queries through the box, with no point of their own
        const Vec3 q{0.31, 0.52, qz};
        std::vector<Index> want, hits;
        for (std::size_t j = 0; j < c.pos.size(); ++j) {
          Vec3 d = q - c.pos[j];
          if (periodic_z) d.z -= std::round(d.z);  // the nearest image (the reach is far below half the period)
          if (norm2(d) < radius * radius) want.push_back(static_cast<Index>(j));
        }
        grid.for_each_neighbour(q, radius, [&](Index j, const Vec3&, double) { hits.push_back(j); });
        std::sort(hits.begin(), hits.end());
        EXPECT_EQ(hits, want) << "query at z = " << qz << ", slab " << z0 << " .. " << z1;
      }
      expect_write_blocks_disjoint(c, radius);
    }
  }
}

// Wall particles 1e19 m apart (a fuzzed dp) asked for more cells than a
// size_t counts: the product wrapped, the grid was too small and build()
// wrote past it. The grid is coarsened instead, and still finds neighbours.
TEST(NeighbourGrid, HugeExtentIsCoarsenedNotOverflowed) {
  const std::vector<Vec3> pos = {{-1e19, -1e19, -1e19}, {1e19, 1e19, 1e19}, {0, 0, 0}, {0.05, 0, 0}};
  NeighbourGrid grid;
  grid.configure(3, pos[0], pos[1], 0.1);
  grid.build(pos);
  std::vector<Index> hits;
  grid.for_each_neighbour(pos[2], 0.1, [&](Index j, const Vec3&, double) { hits.push_back(j); });
  std::sort(hits.begin(), hits.end());
  EXPECT_EQ(hits, (std::vector<Index>{2, 3}));
}

}  // namespace
}  // namespace talus
