// Runs under mpirun (2 and 3 ranks in ctest): every rank builds the same
// lattice, the exchange spreads it, and each check compares with the whole
// lattice that every rank still knows.
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <vector>

#include "mpi/rank_exchange.hpp"
#include "talus/particles.hpp"

namespace talus::mpi {
namespace {

constexpr double kSpacing = 0.1;

// A 2D or 3D lattice of n per axis in [0, n * spacing), ids 0.. in lattice order.
void fill_lattice(ParticleStore& store, int dim, int n) {
  store.require({"value", FieldType::scalar, "", true, true});
  const int nz = dim == 3 ? n : 1;
  store.append(static_cast<std::size_t>(n * n * nz));
  auto x = store.position();
  std::size_t k = 0;
  for (int c = 0; c < nz; ++c)
    for (int b = 0; b < n; ++b)
      for (int a = 0; a < n; ++a)
        x[k++] = {(a + 0.5) * kSpacing, (b + 0.5) * kSpacing, dim == 3 ? (c + 0.5) * kSpacing : 0.0};
}

ExchangeSettings settings_for(int dim, int n, bool periodic_x, double reach, const std::string& method = "RCB") {
  ExchangeSettings s;
  s.method = method;
  s.dim = dim;
  s.lo = {0, 0, 0};
  s.hi = {n * kSpacing, n * kSpacing, dim == 3 ? n * kSpacing : 0.0};
  s.periodic = {periodic_x, false, false};
  s.cell = 2.0 * kSpacing;
  s.reach = reach;
  return s;
}

std::vector<std::uint64_t> all_owned_ids(const ParticleStore& store) {
  const int owned = static_cast<int>(store.owned_size());
  int ranks = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  std::vector<int> counts(static_cast<std::size_t>(ranks)), at(static_cast<std::size_t>(ranks));
  MPI_Allgather(&owned, 1, MPI_INT, counts.data(), 1, MPI_INT, MPI_COMM_WORLD);
  int total = 0;
  for (int r = 0; r < ranks; ++r) {
    at[static_cast<std::size_t>(r)] = total;
    total += counts[static_cast<std::size_t>(r)];
  }
  std::vector<std::uint64_t> ids(static_cast<std::size_t>(total));
  MPI_Allgatherv(store.ids().data(), owned, MPI_UINT64_T, ids.data(), counts.data(), at.data(), MPI_UINT64_T,
                 MPI_COMM_WORLD);
  return ids;
}

// Every particle of the whole lattice is owned by exactly one rank.
void expect_one_owner_each(const ParticleStore& store, const ParticleStore& whole) {
  auto ids = all_owned_ids(store);
  std::sort(ids.begin(), ids.end());
  ASSERT_EQ(ids.size(), whole.size());
  for (std::size_t k = 0; k < ids.size(); ++k) ASSERT_EQ(ids[k], k);
}

double distance(const Vec3& a, const Vec3& b, const ExchangeSettings& s) {
  double d2 = 0.0;
  for (int k = 0; k < 3; ++k) {
    double d = a[k] - b[k];
    if (s.periodic[k]) {
      const double L = s.hi[k] - s.lo[k];
      d -= L * std::round(d / L);
    }
    d2 += d * d;
  }
  return std::sqrt(d2);
}

// Every owned particle's neighbours within `radius` (in the whole lattice
// `whole`, moved as the store was) are on this rank, owned or in the halo.
int missing_neighbours(const ParticleStore& store, const ParticleStore& whole, double radius,
                       const ExchangeSettings& s) {
  std::set<std::uint64_t> here(store.ids().begin(), store.ids().end());
  int missing = 0;
  const auto wx = whole.position();
  for (std::size_t i = 0; i < store.owned_size(); ++i) {
    const Vec3 xi = store.position()[i];
    for (std::size_t j = 0; j < whole.size(); ++j)
      if (distance(xi, wx[j], s) <= radius && !here.count(whole.ids()[j])) ++missing;
  }
  return missing;
}

// Dimension, periodic x, Zoltan's method.
class RankExchangeTest : public ::testing::TestWithParam<std::tuple<int, bool, std::string>> {};

TEST_P(RankExchangeTest, EveryParticleHasOneOwnerAndEveryNeighbourIsThere) {
  const auto [dim, periodic, method] = GetParam();
  const int n = dim == 3 ? 12 : 30;
  const double radius = 2.0 * kSpacing, skin = 0.5 * kSpacing;
  const ExchangeSettings s = settings_for(dim, n, periodic, radius + skin, method);
  ParticleStore store, whole;
  fill_lattice(store, dim, n);
  fill_lattice(whole, dim, n);
  RankExchange exchange(MPI_COMM_WORLD, s);
  ParticleStore* stores[] = {&store};
  const float weights[] = {1.0f};
  exchange.scatter(stores, weights);
  exchange.build_halos(stores);

  // One owner each.
  expect_one_owner_each(store, whole);
  // Balanced: Zoltan's tolerance is 10 %; a lattice splits within one cell row.
  const double share = static_cast<double>(store.owned_size()) * exchange.ranks() / static_cast<double>(whole.size());
  EXPECT_LT(std::abs(share - 1.0), 0.25) << "rank " << exchange.rank() << " owns " << store.owned_size();
  if (exchange.ranks() > 1) EXPECT_GT(store.halo_size(), 0u);
  EXPECT_EQ(missing_neighbours(store, whole, radius, s), 0);

  // Halo values come from their owners.
  auto value = store.scalar("value");
  for (std::size_t i = 0; i < store.owned_size(); ++i) value[i] = 3.0 * static_cast<double>(store.ids()[i]) + 0.25;
  for (std::size_t i = store.owned_size(); i < store.size(); ++i) value[i] = -1.0;
  const std::vector<std::string> fields{"value"};
  exchange.refresh_halo(store, fields);
  for (std::size_t i = store.owned_size(); i < store.size(); ++i)
    ASSERT_EQ(value[i], 3.0 * static_cast<double>(store.ids()[i]) + 0.25);

  // Everyone moves by less than half the skin: the halo still holds every neighbour.
  auto move = [&](ParticleStore& st, std::size_t count) {
    auto x = st.position();
    for (std::size_t i = 0; i < count; ++i) {
      const double t = static_cast<double>(st.ids()[i]);
      x[i].x += 0.24 * skin * std::sin(t);
      x[i].y += 0.24 * skin * std::cos(1.3 * t);
      if (periodic) x[i].x = std::fmod(x[i].x + s.hi.x, s.hi.x);
    }
  };
  move(store, store.size());
  move(whole, whole.size());
  EXPECT_EQ(missing_neighbours(store, whole, radius, s), 0);

  // Migration by the same cuts, then a new halo: still one owner each and nothing missing.
  exchange.migrate(stores);
  exchange.build_halos(stores);
  expect_one_owner_each(store, whole);
  EXPECT_EQ(missing_neighbours(store, whole, radius, s), 0);
  // Every field travelled with its particle.
  for (std::size_t i = 0; i < store.owned_size(); ++i)
    ASSERT_EQ(store.scalar("value")[i], 3.0 * static_cast<double>(store.ids()[i]) + 0.25);
}

TEST(RankExchangeGather, RankZeroHoldsEveryParticleUntilReleased) {
  const int n = 20;
  const ExchangeSettings s = settings_for(2, n, false, 0.25);
  ParticleStore store;
  fill_lattice(store, 2, n);
  RankExchange exchange(MPI_COMM_WORLD, s);
  ParticleStore* stores[] = {&store};
  const float weights[] = {1.0f};
  exchange.scatter(stores, weights);
  exchange.build_halos(stores);
  const std::size_t own = store.owned_size();
  const std::vector<std::uint64_t> own_ids(store.ids().begin(), store.ids().begin() + static_cast<std::ptrdiff_t>(own));
  exchange.gather_to_root(stores);
  EXPECT_EQ(store.halo_size(), 0u);
  if (exchange.rank() == 0) {
    std::vector<std::uint64_t> ids(store.ids().begin(), store.ids().end());
    std::sort(ids.begin(), ids.end());
    ASSERT_EQ(ids.size(), static_cast<std::size_t>(n * n));
    for (std::size_t k = 0; k < ids.size(); ++k) ASSERT_EQ(ids[k], k);
    // Positions came with their ids.
    for (std::size_t i = 0; i < store.size(); ++i) {
      const std::uint64_t id = store.ids()[i];
      ASSERT_DOUBLE_EQ(store.position()[i].x, (static_cast<double>(id % n) + 0.5) * kSpacing);
    }
  } else {
    EXPECT_EQ(store.size(), own);
  }
  exchange.release_gathered(stores);
  ASSERT_EQ(store.size(), own);
  for (std::size_t i = 0; i < own; ++i) ASSERT_EQ(store.ids()[i], own_ids[i]);
}

INSTANTIATE_TEST_SUITE_P(Lattices, RankExchangeTest,
                         ::testing::Combine(::testing::Values(2, 3), ::testing::Bool(),
                                            ::testing::Values("RCB", "RIB", "HSFC")));

// New cuts by a cost that is not uniform: a corner square of the lattice (9 %
// of it) costs ten times the rest. Each rank's cost comes within Zoltan's tolerance and a cell
// of the mean (it never splits a cell), one owner each, nothing missing.
class RankExchangeBalance : public ::testing::TestWithParam<std::string> {};

TEST_P(RankExchangeBalance, UnevenCostIsSharedOutEvenly) {
  const int n = 30;
  const double radius = 2.0 * kSpacing;
  const ExchangeSettings s = settings_for(2, n, false, radius + 0.5 * kSpacing, GetParam());
  ParticleStore store, whole;
  fill_lattice(store, 2, n);
  fill_lattice(whole, 2, n);
  RankExchange exchange(MPI_COMM_WORLD, s);
  ParticleStore* stores[] = {&store};
  const float weights[] = {1.0f};
  exchange.scatter(stores, weights);
  const double corner = 0.3 * n * kSpacing;
  auto cost_of = [&](const Vec3& x) { return x.x < corner && x.y < corner ? 10.0f : 1.0f; };
  double total = 0.0;
  for (const Vec3& x : whole.position()) total += cost_of(x);
  const double mean = total / exchange.ranks();
  auto busiest_cost = [&] {
    double mine = 0.0, busiest = 0.0;
    for (std::size_t i = 0; i < store.owned_size(); ++i) mine += cost_of(store.position()[i]);
    MPI_Allreduce(&mine, &busiest, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
    return busiest;
  };
  // Cut by particle count, the rank with the dear corner carries far more than the mean.
  if (exchange.ranks() > 1) EXPECT_GT(busiest_cost() / mean, 1.3);

  std::vector<float> cost;
  for (const Vec3& x : store.position()) cost.push_back(cost_of(x));
  exchange.balance(stores, cost);
  exchange.build_halos(stores);

  expect_one_owner_each(store, whole);
  EXPECT_EQ(missing_neighbours(store, whole, radius, s), 0);
  // Within Zoltan's 10 % and one cell (2 x 2 particles here) of the dearest kind.
  const double cell_cost = 4 * 10.0;
  EXPECT_LT(busiest_cost(), 1.1 * mean + cell_cost);
}

INSTANTIATE_TEST_SUITE_P(Methods, RankExchangeBalance, ::testing::Values("RCB", "RIB", "HSFC"));

TEST(RankExchangeReductions, SumInRankOrderGivesTheSameBitsEverywhere) {
  RankExchange exchange(MPI_COMM_WORLD, settings_for(2, 4, false, 0.1));
  const double mine = 0.1 * (exchange.rank() + 1);
  double expected = 0.0;
  for (int r = 0; r < exchange.ranks(); ++r) expected += 0.1 * (r + 1);
  EXPECT_EQ(exchange.sum(mine), expected);
  EXPECT_EQ(exchange.sum(std::uint64_t(exchange.rank() + 1)),
            std::uint64_t(exchange.ranks() * (exchange.ranks() + 1) / 2));
  EXPECT_EQ(exchange.max(mine), 0.1 * exchange.ranks());
  EXPECT_EQ(exchange.min(mine), 0.1);
}

// The force on each block, six numbers per block, summed element by element in
// one message: each element as the scalar sum in rank order would give it.
TEST(RankExchangeReductions, VectorSumIsTheScalarSumOfEachElement) {
  RankExchange exchange(MPI_COMM_WORLD, settings_for(2, 4, false, 0.1));
  std::vector<double> mine(7);
  for (std::size_t k = 0; k < mine.size(); ++k) mine[k] = 0.1 * (exchange.rank() + 1) + 1e-3 * double(k);
  std::vector<double> summed = mine;
  exchange.sum(std::span<double>(summed));
  for (std::size_t k = 0; k < mine.size(); ++k) EXPECT_EQ(summed[k], exchange.sum(mine[k])) << "element " << k;
  exchange.sum(std::span<double>());  // nothing to sum still takes part in the message
}

}  // namespace
}  // namespace talus::mpi

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  ::testing::InitGoogleTest(&argc, argv);
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  // One report: the other ranks' results still decide the exit status.
  if (rank != 0) delete ::testing::UnitTest::GetInstance()->listeners().Release(
      ::testing::UnitTest::GetInstance()->listeners().default_result_printer());
  const int failed = RUN_ALL_TESTS();
  int any = 0;
  MPI_Allreduce(&failed, &any, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  MPI_Finalize();
  return any;
}
