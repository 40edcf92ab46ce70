// The hydrostatic pressure a fluid starts with ("hydrostatic": true in a
// scene): at each particle, g times the mass per unit area of the fluid above
// its centre in its vertical column, its own half layer included, summed over
// every fluid body. A layer lying under another body therefore carries that
// body's weight (sediment under water); the sum restarts below an air gap
// taller than half a spacing, since a body above a gap does not rest on the
// one below.
//
// Columns are bins as wide as the finest spacing, across the directions
// normal to gravity; a particle's footprint, its own spacing wide, is shared
// among the bins it overlaps, so bodies of different spacings stack too. For
// one body under a flat free surface this is rho g (top - z), top half a
// spacing above the highest particle.
#pragma once

#include <span>
#include <vector>

#include "talus/config.hpp"
#include "talus/vec3.hpp"

namespace talus {

// Pressure (Pa) of each particle: positions, spacing (m) and density
// (kg/m^3) per particle, gravity (m/s^2), dimension 2 or 3 (in 2D gravity lies
// in the x-y plane). Zero everywhere without gravity.
TALUS_API std::vector<double> hydrostatic_pressure(std::span<const Vec3> position, std::span<const double> spacing,
                                                   std::span<const double> density, Vec3 gravity, int dim);

}  // namespace talus
