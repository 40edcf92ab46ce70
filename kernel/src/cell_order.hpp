// The order that sorts points by the grid cell they fall in (z, then y, then
// x), for re-sorting the particle store so that neighbours lie near each other
// in memory. Its scratch is a count per row of cells and per column, freed on
// return: a re-sort costs no memory between re-sorts.
#pragma once

#include <span>
#include <vector>

#include "talus/config.hpp"
#include "talus/vec3.hpp"

namespace talus {

// Cells of edge about `cell` over [lo, hi]; points beyond it go to the edge cells.
TALUS_API std::vector<Index> cell_order(std::span<const Vec3> x, const Vec3& lo, const Vec3& hi, double cell, int dim);

}  // namespace talus
