// Fits the fluid's start lattice to a block's surface: faces, edges and
// corners (issue 8, buoyancy).
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
// The fix moves the fluid, not the block, by a smooth map x' = x + D(x) of
// the whole lattice near the block, D = sum over faces f of -n_f a_f w_f:
// - a_f(s), the shift towards face f of a point at distance s from its
//   plane: the row k = floor(s/dp - 1/2) >= 0 at s = (1/2 + k + phi) dp moves
//   by phi dp (1 - k/K), so the first row sits exactly dp/2 outside the face
//   and the lattice is stretched back to its own spacing over K rows. Past
//   the face's plane (rows k < 0, only beside the block: the fluid under a
//   box next to its side face) the shift stays phi dp for one row, so the
//   row beyond the plane sits dp/2 past it as the first row sits dp/2 before
//   it, then falls to 0 over K rows (the lattice is compressed there), or
//   fewer: not past the block's middle (the maps of opposite faces would add
//   up) nor up to a free surface beside the block (moving it adds water);
// - w_f(e), the weight at a lateral distance e of the point's foot beyond
//   the face's edges (measured to each neighbouring plane, so a corner counts
//   as its largest): 1 over the face and for the first row beyond an edge,
//   falling to 0 over K rows. Only towards a face that is fitted too: the
//   fluid beside a face on the lattice keeps its place.
// Beside an edge the maps of both faces act, so the fluid there is fitted to
// both (the first row along the edge sits dp/2 from each face, a corner's
// dp/2 from all three) and no void stays along the edges: moving only the
// fluid over a face left a (phi dp)^2 void along every edge where both faces
// are off the lattice (floating_box_draft at dp 0.03: 4 % high). The map is
// smooth and monotone (stretch 1 + phi/K, compression 1 - phi/K per face),
// so no two particles collide (moving the fluid over an edge along both
// normals without tapering did: +14 %). Each moved particle's mass is
// multiplied by det(I + grad D) (central differences over the lattice
// spacing), so the fluid's SPH volume m/rho matches the space it covers: the
// void is filled with water, as the scene meant. A hydrostatic start keeps
// its pressure consistent: p += rho0 g.(x' - x). Faces on the lattice
// (phi = 0) and faces without fluid over them (a floating box's top) are not
// fitted. Blocks with a fitted face not aligned with the lattice (a tilted
// wedge: phi differs from particle to particle, the map is not smooth) keep
// the face-only fit: the fluid over each face moves along its normal.
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
// marked in `covered` (empty: all faces) that have fluid over them, and to
// their edges and corners; returns the particles moved.
std::size_t fit_fluid_to_faces(World& world, std::size_t block, const std::vector<char>& covered, int material);

}  // namespace talus::coupling
