// GeoTIFF DEMs through GDAL: a grid written as GeoTIFF (with GDAL's own
// writer) reads back exactly like the same grid written as an ESRI ASCII grid,
// north-up or south-up; no-data holes, rotated or non-square cells and files
// that are not rasters are InputErrors naming the file; and the valley scene
// run on a GeoTIFF copy of its DEM gives the same run-out and deposit.
#include <gtest/gtest.h>

#include <gdal_priv.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <initializer_list>
#include <string>

#include "../common/process.hpp"
#include "depth_integrated_sph.hpp"
#include "esri_ascii.hpp"
#include "geotiff.hpp"
#include "talus/error.hpp"
#include "terrain.hpp"

namespace talus::runout {
namespace {

namespace fs = std::filesystem;

fs::path temp_dir() {
  const fs::path dir = fs::temp_directory_path() / "talus_runout_geotiff_tests";
  fs::create_directories(dir);
  return dir;
}

template <class F>
void expect_input_error(F&& f, std::initializer_list<std::string> fragments) {
  try {
    f();
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    for (const auto& frag : fragments) EXPECT_NE(msg.find(frag), std::string::npos) << msg << "\nlacks: " << frag;
  }
}

// Not a plane, so bilinear sampling between centres is a real check; no symmetry
// in x or y, so a flipped row or column order shows.
double surface(double x, double y) { return 300.0 - 0.4 * x + 0.15 * y + 0.002 * x * x - 0.001 * (y - 40) * (y - 40); }

// The shared grid: 7 x 5 cells of 2.5 m, south-west corner at (100, 30).
constexpr int kCols = 7, kRows = 5;
constexpr double kCell = 2.5, kXll = 100.0, kYll = 30.0;

Grid shared_grid() {
  Grid g;
  g.cell = kCell;
  g.x0 = kXll + 0.5 * kCell;
  g.y0 = kYll + 0.5 * kCell;
  g.resize(kCols, kRows, 0.0);
  for (int r = 0; r < kRows; ++r)
    for (int c = 0; c < kCols; ++c) g.at(c, r) = surface(g.x_of(c), g.y_of(r));
  return g;
}

// Writes `g` (row 0 south) as a Float64 GeoTIFF with GDAL. The geotransform is
// the usual north-up one unless `transform` replaces it; south_up stores the
// south row first with a positive pixel height. `hole` puts the no-data value
// into one cell (col, row counted from the south).
struct TiffOptions {
  bool south_up = false;
  const std::array<double, 6>* transform = nullptr;
  int hole_col = -1, hole_row = -1;
};

std::string write_geotiff(const std::string& name, const Grid& g, TiffOptions opt = {}) {
  GDALAllRegister();
  const std::string path = (temp_dir() / name).string();
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GTiff");
  EXPECT_NE(driver, nullptr);
  GDALDataset* ds = driver->Create(path.c_str(), g.ncols, g.nrows, 1, GDT_Float64, nullptr);
  EXPECT_NE(ds, nullptr) << path;
  const double xll = g.x0 - 0.5 * g.cell, yll = g.y0 - 0.5 * g.cell;
  std::array<double, 6> t = opt.south_up ? std::array<double, 6>{xll, g.cell, 0.0, yll, 0.0, g.cell}
                                         : std::array<double, 6>{xll, g.cell, 0.0, yll + g.nrows * g.cell, 0.0, -g.cell};
  if (opt.transform) t = *opt.transform;
  ds->SetGeoTransform(t.data());
  GDALRasterBand* band = ds->GetRasterBand(1);
  band->SetNoDataValue(-9999.0);
  std::vector<double> row(g.ncols);
  for (int file_row = 0; file_row < g.nrows; ++file_row) {
    const int r = opt.south_up ? file_row : g.nrows - 1 - file_row;
    for (int c = 0; c < g.ncols; ++c) row[c] = (c == opt.hole_col && r == opt.hole_row) ? -9999.0 : g.at(c, r);
    EXPECT_EQ(band->RasterIO(GF_Write, 0, file_row, g.ncols, 1, row.data(), g.ncols, 1, GDT_Float64, 0, 0), CE_None);
  }
  GDALClose(ds);
  return path;
}

std::string write_asc(const std::string& name, const Grid& g) {
  const std::string path = (temp_dir() / name).string();
  write_esri_ascii(path, g, 17);
  return path;
}

void expect_same_grid(const Grid& a, const Grid& b) {
  ASSERT_EQ(a.ncols, b.ncols);
  ASSERT_EQ(a.nrows, b.nrows);
  EXPECT_DOUBLE_EQ(a.cell, b.cell);
  EXPECT_NEAR(a.x0, b.x0, 1e-9);
  EXPECT_NEAR(a.y0, b.y0, 1e-9);
  for (int r = 0; r < a.nrows; ++r)
    for (int c = 0; c < a.ncols; ++c) EXPECT_NEAR(a.at(c, r), b.at(c, r), 1e-9) << "col " << c << ", row " << r;
}

// A raster whose size would need more memory than the machine has is refused
// from its header, before the grid is allocated: a sparse GeoTIFF of 10^12
// cells holds no data, so the file is small and nothing is read.
TEST(GeoTiffDem, AHugeRasterIsRefusedBeforeAllocating) {
  GDALAllRegister();
  const std::string path = (temp_dir() / "huge.tif").string();
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GTiff");
  ASSERT_NE(driver, nullptr);
  const char* options[] = {"SPARSE_OK=TRUE", "BIGTIFF=YES", "TILED=YES", "BLOCKXSIZE=4096", "BLOCKYSIZE=4096", nullptr};
  GDALDataset* ds = driver->Create(path.c_str(), 1000000, 1000000, 1, GDT_Float64, const_cast<char**>(options));
  ASSERT_NE(ds, nullptr) << path;
  double transform[6] = {0.0, 1.0, 0.0, 1e6, 0.0, -1.0};
  ds->SetGeoTransform(transform);
  GDALClose(ds);
  ASSERT_LT(fs::file_size(path), 10u << 20);
  expect_input_error([&] { read_geotiff(path, false); },
                     {"error: " + path + ": a DEM of 1000000 x 1000000 cells needs about", "--allow-large"});
}

TEST(GeoTiffDem, GdalIsBuiltIn) { EXPECT_TRUE(geotiff_supported()); }

TEST(GeoTiffDem, ReadsCellSizeOriginAndValuesSouthRowFirst) {
  const Grid g = read_geotiff(write_geotiff("north_up.tif", shared_grid()));
  ASSERT_EQ(g.ncols, kCols);
  ASSERT_EQ(g.nrows, kRows);
  EXPECT_DOUBLE_EQ(g.cell, kCell);
  EXPECT_DOUBLE_EQ(g.x0, kXll + 0.5 * kCell);  // centre of the south-west cell
  EXPECT_DOUBLE_EQ(g.y0, kYll + 0.5 * kCell);
  // Row 0 is the south edge although the file stores the north row first.
  EXPECT_DOUBLE_EQ(g.at(0, 0), surface(101.25, 31.25));
  EXPECT_DOUBLE_EQ(g.at(kCols - 1, kRows - 1), surface(101.25 + 6 * kCell, 31.25 + 4 * kCell));
  EXPECT_DOUBLE_EQ(g.at(2, 3), surface(101.25 + 2 * kCell, 31.25 + 3 * kCell));
}

TEST(GeoTiffDem, EqualsTheSameGridWrittenAsEsriAscii) {
  const Grid shared = shared_grid();
  const Grid tif = read_geotiff(write_geotiff("shared.tif", shared));
  const Grid asc = read_esri_ascii(write_asc("shared.asc", shared));
  expect_same_grid(tif, asc);
  // Bilinear sampling, also outside the centres (edge clamping) and at cell faces.
  for (double x : {99.0, 101.25, 102.0, 104.9, 107.5, 110.3, 117.0, 120.0})
    for (double y : {29.0, 31.25, 33.1, 36.25, 38.8, 42.5, 45.0})
      EXPECT_NEAR(tif.bilinear(x, y), asc.bilinear(x, y), 1e-9) << x << ", " << y;
}

TEST(GeoTiffDem, SouthUpFileGivesTheSameGrid) {
  const Grid shared = shared_grid();
  TiffOptions south_up;
  south_up.south_up = true;
  expect_same_grid(read_geotiff(write_geotiff("south_up.tif", shared, south_up)), shared);
}

TEST(GeoTiffDem, SceneTerrainLoaderReadsATifLikeTheAsc) {
  const Grid shared = shared_grid();
  const auto load = [](const std::string& file) {
    return make_terrain(params_from_json(DepthIntegratedSph::describe(),
                                         R"({"release_thickness": 1, "terrain": {"dem": {"file": ")" + file + R"("}}})",
                                         2));
  };
  const auto tif = load(write_geotiff("loader.tif", shared));
  const auto asc = load(write_asc("loader.asc", shared));
  ASSERT_NE(tif->grid(), nullptr);
  for (double x : {101.25, 103.0, 108.8, 115.0})
    for (double y : {31.25, 34.0, 39.9, 41.25}) {
      EXPECT_NEAR(tif->elevation(x, y), asc->elevation(x, y), 1e-9);
      const Vec3 gt = tif->gradient(x, y), ga = asc->gradient(x, y);
      EXPECT_NEAR(gt.x, ga.x, 1e-9);
      EXPECT_NEAR(gt.y, ga.y, 1e-9);
    }
  // Down the grid's north-south axis the surface rises (dZ/dy > 0 near y = 31):
  // a row flip would turn it round.
  EXPECT_GT(tif->gradient(108.0, 32.0).y, 0.0);
}

TEST(GeoTiffDem, NoDataHoleIsAnErrorNamingTheFile) {
  TiffOptions hole;
  hole.hole_col = 3;
  hole.hole_row = 1;
  const std::string path = write_geotiff("hole.tif", shared_grid(), hole);
  // File row 4 (north first) is grid row 1; column 4 counted from 1.
  expect_input_error([&] { read_geotiff(path); }, {path, "no-data", "row 4", "column 4"});
}

TEST(GeoTiffDem, NonSquareCellsAreAnError) {
  const std::array<double, 6> t = {100.0, 2.5, 0.0, 42.5, 0.0, -3.0};
  TiffOptions opt;
  opt.transform = &t;
  const std::string path = write_geotiff("non_square.tif", shared_grid(), opt);
  expect_input_error([&] { read_geotiff(path); }, {path, "square"});
}

TEST(GeoTiffDem, RotatedGeotransformIsAnError) {
  const std::array<double, 6> t = {100.0, 2.5, 0.3, 42.5, 0.3, -2.5};
  TiffOptions opt;
  opt.transform = &t;
  const std::string path = write_geotiff("rotated.tif", shared_grid(), opt);
  expect_input_error([&] { read_geotiff(path); }, {path, "rotated"});
}

TEST(GeoTiffDem, FileThatIsNotARasterIsAnErrorNamingTheFile) {
  const std::string text = (temp_dir() / "text.tif").string();
  test::write_file(text, "ncols 2\nthis is not a raster\n");
  expect_input_error([&] { read_geotiff(text); }, {text, "GDAL", "raster"});
  // A vector file GDAL knows (GeoJSON) is not a raster either.
  const std::string vector = (temp_dir() / "points.tif").string();
  test::write_file(vector, R"({"type": "FeatureCollection", "features": [{"type": "Feature", "properties": {},
    "geometry": {"type": "Point", "coordinates": [1, 2]}}]})");
  expect_input_error([&] { read_geotiff(vector); }, {vector, "raster"});
  const std::string missing = (temp_dir() / "missing.tif").string();
  fs::remove(missing);
  expect_input_error([&] { read_geotiff(missing); }, {missing});
}

// The shipped valley scene on its .asc DEM and on a GeoTIFF converted from it
// (in this test, with GDAL) gives the same run-out, volume and deposit.
TEST(GeoTiffDem, ValleySceneOnAGeoTiffMatchesTheAsc) {
  const fs::path dir = temp_dir() / "valley";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string asc = std::string(TALUS_SHARE_DIR) + "/dem/runout_valley.asc";
  const Grid dem = read_esri_ascii(asc);
  const std::string tif = write_geotiff("valley/runout_valley.tif", dem);
  ASSERT_NO_FATAL_FAILURE(expect_same_grid(read_geotiff(tif), dem));

  const std::string scene = test::read_file(std::string(TALUS_SHARE_DIR) + "/scenes/runout_valley.json");
  const std::string dem_ref = "../dem/runout_valley.asc";
  const auto at = scene.find(dem_ref);
  ASSERT_NE(at, std::string::npos) << "the valley scene no longer names " << dem_ref;
  struct Run {
    std::string name, dem;
  };
  std::string finish[2];
  Grid deposit[2];
  const Run runs[2] = {{"asc", asc}, {"tif", tif}};
  for (int i = 0; i < 2; ++i) {
    std::string copy = scene;
    copy.replace(at, dem_ref.size(), runs[i].dem);
    const std::string scene_path = (dir / (runs[i].name + ".json")).string();
    test::write_file(scene_path, copy);
    const fs::path out = dir / runs[i].name;
    const auto r = test::run_command("'" + std::string(TALUS_EXE) + "' run '" + scene_path + "' --out '" +
                                     out.string() + "' --threads 1");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const auto line = r.output.find("run-out distance");
    ASSERT_NE(line, std::string::npos) << r.output;
    finish[i] = r.output.substr(line, r.output.find('\n', line) - line);
    deposit[i] = read_esri_ascii((out / "runout_valley_deposit_thickness.asc").string(), true);
  }
  EXPECT_EQ(finish[0], finish[1]);
  expect_same_grid(deposit[0], deposit[1]);
  double total = 0.0;
  for (double v : deposit[0].value) total += v > 0.0 ? v : 0.0;
  EXPECT_GT(total, 0.0) << "no deposit: the comparison would be empty";
}

}  // namespace
}  // namespace talus::runout
