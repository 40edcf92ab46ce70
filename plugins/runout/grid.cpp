#include "grid.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "talus/memory.hpp"

namespace talus::runout {

double Grid::bilinear(double x, double y) const {
  const double fx = std::clamp((x - x0) / cell, 0.0, static_cast<double>(ncols - 1));
  const double fy = std::clamp((y - y0) / cell, 0.0, static_cast<double>(nrows - 1));
  const int i = std::min(static_cast<int>(fx), ncols - 2 < 0 ? 0 : ncols - 2);
  const int j = std::min(static_cast<int>(fy), nrows - 2 < 0 ? 0 : nrows - 2);
  const double tx = ncols > 1 ? fx - i : 0.0, ty = nrows > 1 ? fy - j : 0.0;
  const int i1 = ncols > 1 ? i + 1 : i, j1 = nrows > 1 ? j + 1 : j;
  const double a = at(i, j) + tx * (at(i1, j) - at(i, j));
  const double b = at(i, j1) + tx * (at(i1, j1) - at(i, j1));
  return a + ty * (b - a);
}

// Per DEM cell a run holds the elevation grid, the terrain's control points
// and their two flag bytes (terrain.cpp), the raster layout's copy of the grid
// and the six rasters of RunoutRasters, all 8-byte values but the flags.
constexpr double dem_bytes_per_cell = 8.0 + 8.0 + 2.0 + 8.0 + 6.0 * 8.0;

void require_dem_memory(double cols, double rows, const std::string& path) {
  char what[128];
  std::snprintf(what, sizeof what, "a DEM of %.0f x %.0f cells", cols, rows);
  require_memory(cols * rows * dem_bytes_per_cell, path, what);
}

}  // namespace talus::runout
