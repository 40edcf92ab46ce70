// What a particle costs a rank, for the cuts over the ranks: one for the
// particle itself and one for each pair it takes part in within the search
// radius (fluid with fluid and walls, walls with fluid only, as the pair
// passes go), so a wall particle costs less than a fluid one, and a particle
// on a free surface less than one in the bulk.
#pragma once

#include <vector>

#include "talus/neighbour_grid.hpp"
#include "talus/world.hpp"

namespace talus {

class RankCost {
 public:
  // One cost per owned row: the fluid's rows, then the boundary store's. The
  // pairs are counted over owned and halo rows, so a particle next to a cut
  // costs what it would on one rank.
  const std::vector<float>& measure(const World& world, double radius);
  // The costs of the last measure().
  const std::vector<float>& costs() const { return cost_; }

 private:
  // Kept between rebuilds, so that their buffers are not allocated anew.
  NeighbourGrid fluid_grid_, wall_grid_;
  std::vector<float> cost_;
};

}  // namespace talus
