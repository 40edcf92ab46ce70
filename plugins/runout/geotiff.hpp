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
// edge. No-data cells, rotated or non-square cells, and files that are not
// rasters are InputErrors naming the file.
Grid read_geotiff(const std::string& path);

}  // namespace talus::runout
