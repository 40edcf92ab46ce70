// Fits the fluid's start lattice to a block's faces (issue 8, buoyancy).
//
// DBC boundary particles keep whatever gap the fluid starts with: they push
// the fluid but never pull it, and continuity density holds the near-wall
// fluid in equilibrium at any spacing. The fluid's force on a still block is
// then rho g V_excl, where V_excl is the volume the fluid's particles do not
// cover (each covers dp/2 around its centre), not the block's volume. When a
// face lies between two rows of the fluid lattice (e.g. a face at 7.5 dp),
// removing the fluid closer than dp/2 leaves a void of phi dp (0 <= phi < 1)
// over the face: at dp = 0.02 on a 0.1 m block that was +20 % of rho g V.
//
// The fix moves the fluid, not the block: within K rows of a face, the row
// k = floor(s/dp - 1/2) at distance s = (1/2 + k + phi) dp from the face moves
// to s' = (1/2 + k + phi k/K) dp, so the first row sits exactly dp/2 outside
// the face (its cover ends on the face) and the lattice is stretched back to
// its own spacing over K rows. Each moved particle's mass grows by the
// stretch, (1 + phi/K), so the fluid's SPH volume m/rho matches the space it
// covers: the void is filled with water, as the scene meant. A hydrostatic
// start keeps its pressure consistent: p += rho0 g.(x' - x). Only points whose
// foot lies on the face move (not those over an edge or corner): where two
// faces meeting at an edge are both off the lattice, a (phi dp)^2 void stays
// along the edge (fluid_fit.cpp).
#pragma once

#include <cstddef>
#include <vector>

namespace talus {
class World;
}

namespace talus::coupling {

// Number of fluid rows over which the fit is spread.
inline constexpr int fit_rows = 4;

// Fits the fluid near block `block` (index in world.blocks) to the faces
// marked in `covered` (empty: all faces); returns the particles moved.
std::size_t fit_fluid_to_faces(World& world, std::size_t block, const std::vector<char>& covered, int material);

}  // namespace talus::coupling
