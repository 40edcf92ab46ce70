// GeoTIFF DEMs through GDAL (Debian: libgdal-dev; required unless CMake is
// given -DTALUS_WITH_GDAL=OFF). Without GDAL, reading a .tif is an InputError
// saying so.
#pragma once

#include <string>

#include "grid.hpp"

namespace talus::runout {

bool geotiff_supported();
// First band of a GeoTIFF (any raster GDAL reads) with square cells and no
// rotation, north-up or south-up; rows are flipped so row 0 is the south
// edge. Rotated or non-square cells and files that are not rasters are
// InputErrors naming the file; so are no-data cells unless `allow_nodata`,
// which keeps them as Grid::nodata (as read_esri_ascii does).
Grid read_geotiff(const std::string& path, bool allow_nodata = false);

}  // namespace talus::runout
