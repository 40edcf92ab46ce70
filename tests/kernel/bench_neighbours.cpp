// Neighbour-search throughput: neighbour-grid build (binning + counting sort) and
// query (all pairs within 2h) on a jittered lattice, 2D and 3D, at the
// neighbour counts SPH uses (h/dp = 1.3 with a 2h support: ~21 in 2D, ~97 in 3D).
#include <benchmark/benchmark.h>

#include <random>

#include "talus/neighbour_grid.hpp"

namespace {

std::vector<talus::Vec3> lattice(int dim, int n_side, double dp) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> jitter(-0.1 * dp, 0.1 * dp);
  std::vector<talus::Vec3> pos;
  for (int k = 0; k < (dim == 3 ? n_side : 1); ++k)
    for (int j = 0; j < n_side; ++j)
      for (int i = 0; i < n_side; ++i)
        pos.push_back({(i + 0.5) * dp + jitter(rng), (j + 0.5) * dp + jitter(rng),
                       dim == 3 ? (k + 0.5) * dp + jitter(rng) : 0.0});
  return pos;
}

void configure(talus::NeighbourGrid& cells, int dim, int n_side, double dp, double radius) {
  const double L = n_side * dp;
  cells.configure(dim, {0, 0, 0}, {L, L, dim == 3 ? L : 0.0}, radius);
}

void Build(benchmark::State& state) {
  const int dim = static_cast<int>(state.range(0)), n_side = static_cast<int>(state.range(1));
  const double dp = 0.01, radius = 2.6 * dp;
  const auto pos = lattice(dim, n_side, dp);
  talus::NeighbourGrid cells;
  configure(cells, dim, n_side, dp, radius);
  for (auto _ : state) {
    cells.build(pos);
    benchmark::DoNotOptimize(cells.order().data());
  }
  state.counters["particles/s"] = benchmark::Counter(static_cast<double>(pos.size()), benchmark::Counter::kIsIterationInvariantRate);
}

void Query(benchmark::State& state) {
  const int dim = static_cast<int>(state.range(0)), n_side = static_cast<int>(state.range(1));
  const double dp = 0.01, radius = 2.6 * dp;
  const auto pos = lattice(dim, n_side, dp);
  talus::NeighbourGrid cells;
  configure(cells, dim, n_side, dp, radius);
  cells.build(pos);
  std::size_t pairs = 0;
  for (auto _ : state) {
    pairs = 0;
#pragma omp parallel for reduction(+ : pairs) schedule(static)
    for (std::size_t i = 0; i < pos.size(); ++i) {
      double sum = 0.0;
      cells.for_each_neighbour(pos[i], radius, [&](talus::Index, const talus::Vec3&, double r2) {
        sum += r2;
        ++pairs;
      });
      benchmark::DoNotOptimize(sum);
    }
  }
  state.counters["pairs/s"] = benchmark::Counter(static_cast<double>(pairs), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["neighbours"] = static_cast<double>(pairs) / pos.size();
}

}  // namespace

BENCHMARK(Build)->Args({2, 400})->Args({3, 50})->Unit(benchmark::kMillisecond);
BENCHMARK(Query)->Args({2, 400})->Args({3, 50})->Unit(benchmark::kMillisecond)->UseRealTime();
