// What a particle costs a rank, for the cuts over the ranks: one for the
// particle itself and one for each pair it takes part in within the search
// radius (fluid with fluid and walls, walls with fluid only, as the pair
// passes go), so a wall particle costs less than a fluid one, and a particle
// on a free surface less than one in the bulk.
#pragma once

#include <vector>

#include "talus/world.hpp"

namespace talus {

// One cost per owned row: the fluid's rows, then the boundary store's. The
// pairs are counted over owned and halo rows, so a particle next to a cut
// costs what it would on one rank.
std::vector<float> owned_particle_costs(const World& world, double radius);

}  // namespace talus
