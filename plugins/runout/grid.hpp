// A regular raster on cell centres, row 0 at the south (min y) edge, as the
// terrain, the release-thickness raster and the output rasters use it.
// ESRI ASCII files store the north row first; esri_ascii.cpp flips.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace talus::runout {

struct Grid {
  int ncols = 0, nrows = 0;
  double x0 = 0.0, y0 = 0.0;  // centre of cell (0, 0), the south-west cell
  double cell = 1.0;          // square cells, m
  double nodata = -9999.0;
  std::vector<double> value;  // row-major, value[row * ncols + col], row 0 south

  double& at(int col, int row) { return value[static_cast<std::size_t>(row) * ncols + col]; }
  double at(int col, int row) const { return value[static_cast<std::size_t>(row) * ncols + col]; }
  double x_of(int col) const { return x0 + col * cell; }
  double y_of(int row) const { return y0 + row * cell; }
  // Extent of the cell centres (where bilinear interpolation needs no clamping).
  double x_max() const { return x0 + (ncols - 1) * cell; }
  double y_max() const { return y0 + (nrows - 1) * cell; }

  void resize(int cols, int rows, double fill) {
    ncols = cols;
    nrows = rows;
    value.assign(static_cast<std::size_t>(cols) * rows, fill);
  }

  // Bilinear interpolation between cell centres; outside, the edge value.
  double bilinear(double x, double y) const;
};

// Refuses (InputError naming `path`) a DEM of cols x rows cells whose run
// would need more memory than is available, before the grid is allocated.
void require_dem_memory(double cols, double rows, const std::string& path);

}  // namespace talus::runout
