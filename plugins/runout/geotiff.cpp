#include "geotiff.hpp"

#include <cmath>

#include "talus/error.hpp"

#ifdef TALUS_HAVE_GDAL
#include <gdal_priv.h>
#endif

namespace talus::runout {

#ifdef TALUS_HAVE_GDAL

bool geotiff_supported() { return true; }

Grid read_geotiff(const std::string& path) {
  GDALAllRegister();
  GDALDataset* ds = static_cast<GDALDataset*>(GDALOpen(path.c_str(), GA_ReadOnly));
  if (!ds) throw InputError("error: " + path + ": GDAL cannot open it as a raster: " + CPLGetLastErrorMsg());
  struct Close {
    GDALDataset* d;
    ~Close() { GDALClose(d); }
  } close{ds};
  double t[6];
  if (ds->GetGeoTransform(t) != CE_None)
    throw InputError("error: " + path + ": no geotransform; a DEM needs its cell size and origin");
  if (t[2] != 0.0 || t[4] != 0.0 || std::abs(std::abs(t[5]) - t[1]) > 1e-9 * t[1])
    throw InputError("error: " + path + ": only north-up rasters with square cells are supported");
  GDALRasterBand* band = ds->GetRasterBand(1);
  Grid g;
  g.cell = t[1];
  g.resize(ds->GetRasterXSize(), ds->GetRasterYSize(), 0.0);
  if (g.ncols < 2 || g.nrows < 2) throw InputError("error: " + path + ": a DEM needs at least 2 x 2 cells");
  std::vector<double> row(g.ncols);
  int has_nodata = 0;
  const double nodata = band->GetNoDataValue(&has_nodata);
  const bool north_up = t[5] < 0.0;
  for (int r = 0; r < g.nrows; ++r) {
    if (band->RasterIO(GF_Read, 0, r, g.ncols, 1, row.data(), g.ncols, 1, GDT_Float64, 0, 0) != CE_None)
      throw InputError("error: " + path + ": cannot read row " + std::to_string(r + 1));
    const int south_row = north_up ? g.nrows - 1 - r : r;
    for (int c = 0; c < g.ncols; ++c) {
      if ((has_nodata && row[c] == nodata) || !std::isfinite(row[c]))
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

Grid read_geotiff(const std::string& path) {
  throw InputError("error: " + path +
                   ": GeoTIFF DEMs need GDAL, and this build has none (install libgdal-dev and rebuild), or "
                   "convert it: gdal_translate -of AAIGrid DEM.tif DEM.asc");
}

#endif

}  // namespace talus::runout
