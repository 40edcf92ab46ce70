#include "geotiff.hpp"

#include <cmath>
#include <string>
#include <vector>

#include "talus/error.hpp"

#ifdef TALUS_HAVE_GDAL
#include <gdal_priv.h>
#endif

namespace talus::runout {

#ifdef TALUS_HAVE_GDAL

bool geotiff_supported() { return true; }

// Keeps GDAL's own "ERROR n: ..." lines off stderr while reading: its
// message goes into the InputError instead.
struct QuietGdal {
  QuietGdal() { CPLPushErrorHandler(CPLQuietErrorHandler); }
  ~QuietGdal() { CPLPopErrorHandler(); }
};

Grid read_geotiff(const std::string& path, bool allow_nodata) {
  GDALAllRegister();
  const QuietGdal quiet;
  CPLErrorReset();
  const unsigned flags = GDAL_OF_RASTER | GDAL_OF_READONLY;  // a vector file is "not a raster", not a crash
  auto* ds = static_cast<GDALDataset*>(GDALOpenEx(path.c_str(), flags, nullptr, nullptr, nullptr));
  if (!ds) throw InputError("error: " + path + ": GDAL cannot open it as a raster: " + CPLGetLastErrorMsg());
  struct Close {
    GDALDataset* d;
    ~Close() { GDALClose(d); }
  } close{ds};
  if (ds->GetRasterCount() < 1) throw InputError("error: " + path + ": the raster has no band; a DEM needs one");
  double t[6];
  if (ds->GetGeoTransform(t) != CE_None)
    throw InputError("error: " + path + ": no geotransform; a DEM needs its cell size and origin");
  if (t[2] != 0.0 || t[4] != 0.0)
    throw InputError("error: " + path + ": the geotransform is rotated (terms " + std::to_string(t[2]) + ", " +
                     std::to_string(t[4]) + "); only north-up rasters are supported (gdalwarp it first)");
  if (!(t[1] > 0.0) || std::abs(std::abs(t[5]) - t[1]) > 1e-9 * t[1])
    throw InputError("error: " + path + ": cells are " + std::to_string(t[1]) + " x " + std::to_string(std::abs(t[5])) +
                     "; only square cells are supported (resample it first, e.g. gdalwarp -tr)");
  GDALRasterBand* band = ds->GetRasterBand(1);
  if (ds->GetRasterXSize() < 2 || ds->GetRasterYSize() < 2)
    throw InputError("error: " + path + ": a DEM needs at least 2 x 2 cells");
  require_dem_memory(ds->GetRasterXSize(), ds->GetRasterYSize(), path);
  Grid g;
  g.cell = t[1];
  g.resize(ds->GetRasterXSize(), ds->GetRasterYSize(), 0.0);
  std::vector<double> row(g.ncols);
  int has_nodata = 0;
  const double nodata = band->GetNoDataValue(&has_nodata);
  const bool north_up = t[5] < 0.0;
  for (int r = 0; r < g.nrows; ++r) {
    if (band->RasterIO(GF_Read, 0, r, g.ncols, 1, row.data(), g.ncols, 1, GDT_Float64, 0, 0) != CE_None)
      throw InputError("error: " + path + ": cannot read row " + std::to_string(r + 1));
    const int south_row = north_up ? g.nrows - 1 - r : r;
    for (int c = 0; c < g.ncols; ++c) {
      const bool hole = (has_nodata && row[c] == nodata) || !std::isfinite(row[c]);
      if (hole && allow_nodata) {
        g.at(c, south_row) = g.nodata;
        continue;
      }
      if (hole)
        throw InputError("error: " + path + ": no-data value at row " + std::to_string(r + 1) + ", column " +
                         std::to_string(c + 1) + ": the terrain has a hole; fill it before use");
      g.at(c, south_row) = row[c];
    }
  }
  g.x0 = t[0] + 0.5 * t[1];
  g.y0 = north_up ? t[3] + g.nrows * t[5] + 0.5 * t[1] : t[3] + 0.5 * t[1];
  return g;
}

#else

bool geotiff_supported() { return false; }

Grid read_geotiff(const std::string& path, bool) {
  throw InputError("error: " + path +
                   ": GeoTIFF DEMs need GDAL, and this build has none (configured with TALUS_WITH_GDAL=OFF; install "
                   "libgdal-dev and reconfigure with it ON), or "
                   "convert it: gdal_translate -of AAIGrid DEM.tif DEM.asc");
}

#endif

}  // namespace talus::runout
