#include "rank_cost.hpp"

#include <cstddef>

#include "talus/neighbour_grid.hpp"

namespace talus {

namespace {

// Pairs of x with the points binned in `grid`, x itself excluded.
std::size_t pairs_within(const NeighbourGrid& grid, const Vec3& x, double radius) {
  std::size_t count = 0;
  grid.for_each_neighbour(x, radius, [&](Index, const Vec3&, double r2) { count += r2 > 0.0; });
  return count;
}

}  // namespace

std::vector<float> owned_particle_costs(const World& world, double radius) {
  const ParticleStore& fluid = world.fluid;
  const ParticleStore& walls = world.boundary;
  NeighbourGrid fluid_grid, wall_grid;
  fluid_grid.configure(world.dim, world.lo, world.hi, radius, world.periodic);
  wall_grid.configure(world.dim, world.lo, world.hi, radius, world.periodic);
  fluid_grid.build(fluid.position());
  wall_grid.build(walls.position());

  const std::size_t nf = fluid.owned_size(), nw = walls.owned_size();
  std::vector<float> cost(nf + nw);
  const auto xf = fluid.position();
  const auto xw = walls.position();
#pragma omp parallel for schedule(static) if (nf > 4096)
  for (std::size_t i = 0; i < nf; ++i)
    cost[i] = static_cast<float>(1 + pairs_within(fluid_grid, xf[i], radius) + pairs_within(wall_grid, xf[i], radius));
#pragma omp parallel for schedule(static) if (nw > 4096)
  for (std::size_t k = 0; k < nw; ++k) cost[nf + k] = static_cast<float>(1 + pairs_within(fluid_grid, xw[k], radius));
  return cost;
}

}  // namespace talus
