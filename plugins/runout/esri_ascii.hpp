// ESRI ASCII grid (.asc) reading and writing. Header keys (case-insensitive):
// ncols, nrows, xllcorner|xllcenter, yllcorner|yllcenter, cellsize,
// optional NODATA_value; then nrows lines of ncols numbers, north row first.
// Every problem is an InputError naming the file and the line.
#pragma once

#include <string>

#include "grid.hpp"

namespace talus::runout {

// Reads a grid. With `allow_nodata` false, a no-data cell is an error naming
// its line, row and column (a DEM with holes cannot carry a flow); with it
// true, no-data cells are kept as Grid::nodata (a thickness raster).
Grid read_esri_ascii(const std::string& path, bool allow_nodata = false);

// Writes to PATH.tmp and renames, so no truncated file is ever left behind.
// Throws RunError naming the path and the system's reason.
void write_esri_ascii(const std::string& path, const Grid& grid, int precision = 6);

}  // namespace talus::runout
