// GeoTIFF DEMs through GDAL (optional: built when CMake finds GDAL, i.e. the
// Debian package libgdal-dev). Without GDAL, reading a .tif is an InputError
// saying so.
#pragma once

#include <string>

#include "grid.hpp"

namespace talus::runout {

bool geotiff_supported();
// First band of a north-up GeoTIFF with square cells; no-data cells are an error.
Grid read_geotiff(const std::string& path);

}  // namespace talus::runout
