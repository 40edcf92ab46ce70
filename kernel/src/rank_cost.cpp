#include "rank_cost.hpp"

#include <cstddef>

namespace talus {

namespace {

// Pairs of x with the points binned in `grid`, x itself excluded.
std::size_t pairs_within(const NeighbourGrid& grid, const Vec3& x, double radius) {
  std::size_t count = 0;
  grid.for_each_neighbour(x, radius, [&](Index, const Vec3&, double r2) { count += r2 > 0.0; });
  return count;
}

}  // namespace

const std::vector<float>& RankCost::measure(const World& world, double radius) {
  const ParticleStore& fluid = world.fluid;
  const ParticleStore& walls = world.boundary;
  fluid_grid_.configure(world.dim, world.lo, world.hi, radius, world.periodic);
  wall_grid_.configure(world.dim, world.lo, world.hi, radius, world.periodic);
  fluid_grid_.build(fluid.position());
  wall_grid_.build(walls.position());

  const std::size_t nf = fluid.owned_size(), nw = walls.owned_size();
  cost_.resize(nf + nw);
  const auto xf = fluid.position();
  const auto xw = walls.position();
#pragma omp parallel for schedule(static) if (nf > 4096)
  for (std::size_t i = 0; i < nf; ++i)
    cost_[i] = static_cast<float>(1 + pairs_within(fluid_grid_, xf[i], radius) + pairs_within(wall_grid_, xf[i], radius));
#pragma omp parallel for schedule(static) if (nw > 4096)
  for (std::size_t k = 0; k < nw; ++k) cost_[nf + k] = static_cast<float>(1 + pairs_within(fluid_grid_, xw[k], radius));
  return cost_;
}

}  // namespace talus
