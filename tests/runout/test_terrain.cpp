// Terrain: ESRI ASCII grids (reading, writing, clear errors), bilinear
// elevation and gradients, analytic surfaces, and the stage's setup checks.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <vector>

#include "depth_integrated_sph.hpp"
#include "esri_ascii.hpp"
#include "runout_world.hpp"
#include "talus/error.hpp"
#include "talus/memory.hpp"
#include "terrain.hpp"

namespace talus::runout {
namespace {

namespace fs = std::filesystem;

std::string write_file(const std::string& name, const std::string& text) {
  const fs::path dir = fs::temp_directory_path() / "talus_runout_tests";
  fs::create_directories(dir);
  const fs::path p = dir / name;
  std::ofstream(p) << text;
  return p.string();
}

// Expects an InputError whose message contains every fragment.
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

// A plane Z = 100 + 0.5 x - 0.25 y sampled on cell centres (corner at 10, 20, cell 2).
std::string plane_asc(const char* nodata_row2 = nullptr) {
  std::string s = "ncols 4\nnrows 3\nxllcorner 10\nyllcorner 20\ncellsize 2\nNODATA_value -9999\n";
  for (int r = 0; r < 3; ++r) {  // north row first
    const double y = 20 + 1 + 2 * (2 - r);
    for (int c = 0; c < 4; ++c) {
      const double x = 10 + 1 + 2 * c;
      if (r == 1 && c == 2 && nodata_row2) s += nodata_row2;
      else s += std::to_string(100 + 0.5 * x - 0.25 * y);
      s += c < 3 ? " " : "\n";
    }
  }
  return s;
}

TEST(EsriAscii, ReadsGeometryAndValuesSouthRowFirst) {
  const Grid g = read_esri_ascii(write_file("plane.asc", plane_asc()));
  EXPECT_EQ(g.ncols, 4);
  EXPECT_EQ(g.nrows, 3);
  EXPECT_DOUBLE_EQ(g.x0, 11.0);
  EXPECT_DOUBLE_EQ(g.y0, 21.0);
  EXPECT_NEAR(g.at(0, 0), 100 + 0.5 * 11 - 0.25 * 21, 1e-6);
  EXPECT_NEAR(g.at(3, 2), 100 + 0.5 * 17 - 0.25 * 25, 1e-6);
}

TEST(EsriAscii, XllcenterMeansCellCentres) {
  const Grid g = read_esri_ascii(write_file("centre.asc", "ncols 2\nnrows 2\nxllcenter 0\nyllcenter 0\ncellsize 1\n1 2\n3 4\n"));
  EXPECT_DOUBLE_EQ(g.x0, 0.0);
  EXPECT_DOUBLE_EQ(g.at(0, 0), 3.0);  // south-west
  EXPECT_DOUBLE_EQ(g.at(1, 1), 2.0);  // north-east
}

TEST(EsriAscii, WriteThenReadRoundTrips) {
  Grid g = read_esri_ascii(write_file("plane2.asc", plane_asc()));
  const std::string out = (fs::temp_directory_path() / "talus_runout_tests" / "round.asc").string();
  write_esri_ascii(out, g, 12);
  const Grid back = read_esri_ascii(out);
  EXPECT_DOUBLE_EQ(back.x0, g.x0);
  EXPECT_DOUBLE_EQ(back.y0, g.y0);
  for (std::size_t k = 0; k < g.value.size(); ++k) EXPECT_NEAR(back.value[k], g.value[k], 1e-9);
  EXPECT_FALSE(fs::exists(out + ".tmp"));
}

TEST(EsriAscii, NoDataHoleIsAnErrorNamingFileLineRowAndColumn) {
  const std::string path = write_file("hole.asc", plane_asc("-9999"));
  expect_input_error([&] { read_esri_ascii(path); }, {path + ":8:", "no-data", "row 2, column 3", "hole"});
  // A thickness raster may have no-data cells.
  const Grid g = read_esri_ascii(path, true);
  EXPECT_EQ(g.at(2, 1), -9999.0);
}

TEST(EsriAscii, WrongHeaderIsAnErrorNamingTheLine) {
  const std::string bad_key = write_file("badkey.asc", "ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncelsize 1\n1 2\n3 4\n");
  expect_input_error([&] { read_esri_ascii(bad_key); }, {bad_key + ":5:", "unknown header key 'celsize'", "cellsize"});
  const std::string no_cell = write_file("nocell.asc", "ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\n1 2\n3 4\n");
  expect_input_error([&] { read_esri_ascii(no_cell); }, {no_cell, "no 'cellsize'"});
  const std::string bad_value = write_file("badvalue.asc", "ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize x\n");
  expect_input_error([&] { read_esri_ascii(bad_value); }, {bad_value + ":5:", "KEY NUMBER"});
  expect_input_error([&] { read_esri_ascii("/nonexistent/dem.asc"); }, {"/nonexistent/dem.asc", "cannot open"});
}

TEST(EsriAscii, SizeMismatchIsAnErrorNamingTheLine) {
  const std::string short_row =
      write_file("short.asc", "ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2 3\n4 5\n");
  expect_input_error([&] { read_esri_ascii(short_row); }, {short_row + ":7:", "has 2 values, ncols = 3", "size mismatch"});
  const std::string few_rows = write_file("few.asc", "ncols 2\nnrows 3\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2\n3 4\n");
  expect_input_error([&] { read_esri_ascii(few_rows); }, {few_rows, "found 2 rows, header says nrows = 3"});
  const std::string many_rows =
      write_file("many.asc", "ncols 2\nnrows 1\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2\n3 4\n");
  expect_input_error([&] { read_esri_ascii(many_rows); }, {many_rows, "nrows"});
}

// A header that promises a huge grid is refused before the grid is allocated:
// by the file's size when the values cannot be there, by the memory the run
// would need when they could.
TEST(EsriAscii, AHugeHeaderIsRefusedBeforeAllocating) {
  const std::string path = write_file("huge.asc", "ncols 50000\nnrows 50000\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2\n3 4\n");
  expect_input_error([&] { read_esri_ascii(path); },
                     {"error: " + path + ": the header promises 50000 x 50000 values, but the file holds only",
                      "size mismatch"});
  const std::string wide = write_file("wide.asc", "ncols 3e9\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2\n");
  expect_input_error([&] { read_esri_ascii(wide); }, {"error: " + wide + ": ncols and nrows must be at most"});
}

TEST(DemMemory, AGridNeedingMoreThanTheMachineHasIsRefusedUnlessAllowed) {
  expect_input_error([] { require_dem_memory(1e6, 1e6, "valley.tif"); },
                     {"error: valley.tif: a DEM of 1000000 x 1000000 cells needs about", "available", "--allow-large"});
  EXPECT_NO_THROW(require_dem_memory(100, 100, "small.asc"));
  talus::set_memory_check(false);
  EXPECT_NO_THROW(require_dem_memory(1e6, 1e6, "valley.tif"));
  talus::set_memory_check(true);
}

TEST(GridTerrain, BilinearElevationAndGradientAreExactOnAPlane) {
  auto t = make_grid_terrain(read_esri_ascii(write_file("plane3.asc", plane_asc())), "plane3.asc");
  for (double x : {11.0, 12.3, 14.9, 17.0})
    for (double y : {21.0, 22.7, 25.0}) {
      EXPECT_NEAR(t->elevation(x, y), 100 + 0.5 * x - 0.25 * y, 1e-6);
      const Vec3 g = t->gradient(x, y);
      EXPECT_NEAR(g.x, 0.5, 1e-6);
      EXPECT_NEAR(g.y, -0.25, 1e-6);
    }
  ASSERT_NE(t->grid(), nullptr);
  // Batch sampling gives the same values.
  const std::vector<Vec3> pos = {{12.0, 22.0, 0.0}, {16.5, 24.5, 0.0}};
  double z[2];
  Vec3 g[2];
  Hessian h[2];
  t->sample(pos, z, g, h);
  EXPECT_NEAR(z[1], 100 + 0.5 * 16.5 - 0.25 * 24.5, 1e-6);
  EXPECT_NEAR(g[0].x, 0.5, 1e-6);
}

// The DEM surface is the cubic B-spline of the DEM values: a quadratic
// surface comes back with its curvature exact and its elevation offset by
// cell^2 (Zxx + Zyy) / 6.
TEST(GridTerrain, SmoothedBicubicHasTheCurvatureOfAQuadraticSurface) {
  const double cell = 2.0;
  auto quadratic = [](double x, double y) { return 0.01 * x * x - 0.004 * x * y + 0.02 * y * y + 0.3 * x; };
  std::string text = "ncols 20\nnrows 16\nxllcorner 0\nyllcorner 0\ncellsize 2\n";
  for (int r = 15; r >= 0; --r)
    for (int c = 0; c < 20; ++c)
      text += std::to_string(quadratic((c + 0.5) * cell, (r + 0.5) * cell)) + (c < 19 ? " " : "\n");
  auto t = make_grid_terrain(read_esri_ascii(write_file("quadratic.asc", text), true), "quadratic.asc");
  for (double x : {9.0, 17.3, 24.9})
    for (double y : {8.0, 13.7, 22.1}) {
      const Hessian h = t->hessian(x, y);
      EXPECT_NEAR(h.xx, 0.02, 1e-6);
      EXPECT_NEAR(h.xy, -0.004, 1e-6);
      EXPECT_NEAR(h.yy, 0.04, 1e-6);
      EXPECT_NEAR(t->elevation(x, y), quadratic(x, y) + cell * cell * (0.02 + 0.04) / 6.0, 1e-4);
      EXPECT_NEAR(t->gradient(x, y).x, 0.02 * x - 0.004 * y + 0.3, 1e-6);
    }
}

// Cell-scale noise (a +-1 cm checkerboard on a plane, the grid's shortest
// wavelength) comes back at a third of its height at the cell centres, and
// the curvature it adds stays that of the damped ripple: the surface does
// not turn raster noise into large second derivatives.
TEST(GridTerrain, SmoothedBicubicDampsCellScaleNoise) {
  const double cell = 2.0, noise = 0.01;
  std::string text = "ncols 16\nnrows 16\nxllcorner 0\nyllcorner 0\ncellsize 2\n";
  for (int r = 15; r >= 0; --r)
    for (int c = 0; c < 16; ++c)
      text += std::to_string(0.2 * (c + 0.5) * cell + ((r + c) % 2 ? noise : -noise)) + (c < 15 ? " " : "\n");
  auto t = make_grid_terrain(read_esri_ascii(write_file("noisy.asc", text), true), "noisy.asc");
  double worst_z = 0.0, worst_h = 0.0;
  for (int r = 3; r < 13; ++r)
    for (int c = 3; c < 13; ++c) {
      const double x = (c + 0.5) * cell, y = (r + 0.5) * cell;
      worst_z = std::max(worst_z, std::abs(t->elevation(x, y) - 0.2 * x));
      const Hessian h = t->hessian(x, y);
      worst_h = std::max({worst_h, std::abs(h.xx), std::abs(h.yy), std::abs(h.xy)});
    }
  EXPECT_NEAR(worst_z, noise / 9.0, 1e-9);  // (1/3 per axis)^2 for a checkerboard
  // An interpolating surface through the noise has |Z_xx| = 8 noise / cell^2 at the nodes.
  EXPECT_LT(worst_h, 8.0 * noise / (cell * cell) / 3.0);
}

// A no-data cell leaves the surface undefined where the 4 x 4 control points
// include it; elsewhere the surface is there.
TEST(GridTerrain, NoDataCellLeavesTheSurfaceUndefinedAroundIt) {
  auto t = make_grid_terrain(read_esri_ascii(write_file("hole_dem.asc", plane_asc("-9999")), true), "hole_dem.asc");
  // The hole is the cell centred at (15, 23).
  EXPECT_FALSE(t->defined(15.0, 23.0));
  EXPECT_FALSE(std::isfinite(t->elevation(14.0, 22.5)));
  double z[1];
  Vec3 g[1];
  Hessian h[1];
  const std::vector<Vec3> pos = {{15.5, 23.0, 0.0}};
  t->sample(pos, z, g, h);
  EXPECT_FALSE(std::isfinite(z[0]));
  // Well away from it (beyond two cells), defined and still the plane.
  auto full = make_grid_terrain(read_esri_ascii(write_file("no_hole_dem.asc", plane_asc()), true), "no_hole_dem.asc");
  EXPECT_TRUE(full->defined(15.0, 23.0));
}

// A particle gone non-finite within a step is sampled before the host stops
// the run: the surface is undefined there (NaN), not an index out of bounds.
TEST(GridTerrain, NonFinitePointHasNoSurface) {
  auto t = make_grid_terrain(read_esri_ascii(write_file("nan_point.asc", plane_asc()), true), "nan_point.asc");
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  for (const Vec3 p : {Vec3{nan, 1.0, 0.0}, Vec3{1.0, nan, 0.0}, Vec3{inf, -inf, 0.0}}) {
    EXPECT_FALSE(t->defined(p.x, p.y));
    EXPECT_TRUE(std::isnan(t->elevation(p.x, p.y)));
    std::vector<Vec3> pos(5000, p);  // enough for the parallel path
    std::vector<double> z(pos.size());
    std::vector<Vec3> g(pos.size());
    std::vector<Hessian> h(pos.size());
    t->sample(pos, z.data(), g.data(), h.data());
    EXPECT_TRUE(std::isnan(z.back()));
  }
}

TEST(StageSetup, RasterPrefixOutsideTheOutputFolderIsRefused) {
  expect_input_error([] {
    params_from_json(DepthIntegratedSph::describe(),
                     R"({"terrain": {"plane": {"slope": 0}}, "release_thickness": 1, "rasters": "../maps/r"})", 2);
  }, {"/rasters: ", "a path, not a file name"});
}

TEST(StageSetup, ReleaseOutsideTheDemIsAnError) {
  const std::string dem = write_file("small_dem.asc", plane_asc());
  test::RunoutWorld w({0, 0, 0}, {100, 100, 0}, 1.0);
  const int m = w.add_material("debris", 2000.0, nullptr);
  w.fill_box({50.0, 50.0, 0}, {60.0, 60.0, 0}, m);
  expect_input_error(
      [&] { w.make_stage(R"({"terrain": {"dem": {"file": ")" + dem + R"("}}, "release_thickness": 1})", 1.0); },
      {"reaches beyond the DEM", "shrink the domain"});
}

// A domain written from the DEM's own edges (a hand-off's run-out scene) differs from the edges the file's
// 10-digit header gives by rounding only; that is accepted, a millimetre beyond is not.
TEST(StageSetup, DomainOnTheDemEdgesUpToRoundingIsAccepted) {
  const std::string dem = write_file("edge_dem.asc", plane_asc());
  const double ulp = 4e-15;
  for (const double beyond : {ulp, 1e-3}) {
    test::RunoutWorld w({10.0, 20.0 - beyond, 0}, {18.0 + beyond, 26.0, 0}, 0.5);
    const int m = w.add_material("debris", 2000.0, nullptr);
    w.fill_box({13.0, 22.0, 0}, {15.0, 24.0, 0}, m);
    auto make = [&] { w.make_stage(R"({"terrain": {"dem": {"file": ")" + dem + R"("}}, "release_thickness": 1})", 1.0); };
    if (beyond == ulp)
      EXPECT_NO_THROW(make());
    else
      expect_input_error(make, {"reaches beyond the DEM", "shrink the domain"});
  }
}

TEST(StageSetup, ReleaseWhereTheDemHasNoSurfaceIsAnErrorNamingTheFileAndPointer) {
  const std::string dem = write_file("release_hole.asc", plane_asc("-9999"));
  test::RunoutWorld w({10.5, 20.5, 0}, {17.5, 25.5, 0}, 0.5);
  const int m = w.add_material("debris", 2000.0, nullptr);
  w.fill_box({14.0, 22.0, 0}, {16.0, 24.0, 0}, m);
  expect_input_error(
      [&] { w.make_stage(R"({"terrain": {"dem": {"file": ")" + dem + R"("}}, "release_thickness": 1})", 1.0); },
      {"/terrain/dem/file", dem, "no surface", "no-data", "mass0"});
}

std::unique_ptr<Terrain> analytic(const std::string& json) {
  return make_terrain(params_from_json(DepthIntegratedSph::describe(),
                                       R"({"release_thickness": 1, "terrain": )" + json + "}", 2));
}

TEST(AnalyticTerrain, InclinedPlaneDescendsTowardsPlusX) {
  auto t = analytic(R"({"plane": {"slope": 30, "elevation": 5}})");
  EXPECT_NEAR(t->elevation(2.0, 7.0), 5.0 - 2.0 * std::tan(std::numbers::pi / 6), 1e-12);
  EXPECT_NEAR(t->gradient(0.0, 0.0).x, -std::tan(std::numbers::pi / 6), 1e-12);
  EXPECT_EQ(t->grid(), nullptr);
}

TEST(AnalyticTerrain, PlaneWithRunoutIsContinuousAndFlatBeyondTheFoot) {
  const double s = std::tan(35.0 * std::numbers::pi / 180.0);
  auto sharp = analytic(R"({"plane_runout": {"slope": 35, "foot": 2}})");
  EXPECT_NEAR(sharp->elevation(0.0, 0.0), 2.0 * s, 1e-12);
  EXPECT_EQ(sharp->elevation(2.5, 0.0), 0.0);
  EXPECT_EQ(sharp->gradient(2.5, 0.0).x, 0.0);
  auto smooth = analytic(R"({"plane_runout": {"slope": 35, "foot": 2, "transition_length": 1}})");
  // Same straight slope far up; continuous elevation and gradient at both ends of the blend.
  EXPECT_NEAR(smooth->elevation(0.0, 0.0), 2.0 * s, 1e-12);
  for (double x : {1.5, 2.5}) {
    EXPECT_NEAR(smooth->elevation(x - 1e-9, 0.0), smooth->elevation(x + 1e-9, 0.0), 1e-8);
    EXPECT_NEAR(smooth->gradient(x - 1e-9, 0.0).x, smooth->gradient(x + 1e-9, 0.0).x, 1e-8);
  }
  EXPECT_NEAR(smooth->gradient(2.0, 0.0).x, -0.5 * s, 1e-12);
}

TEST(AnalyticTerrain, ChannelHasParabolicBanks) {
  auto t = analytic(R"({"channel": {"slope": 10, "axis": 1, "half_width": 2, "bank_height": 3}})");
  const double s = std::tan(10.0 * std::numbers::pi / 180.0);
  EXPECT_NEAR(t->elevation(4.0, 3.0), -4.0 * s + 3.0, 1e-12);
  EXPECT_NEAR(t->elevation(4.0, 1.0), -4.0 * s, 1e-12);
  EXPECT_NEAR(t->gradient(0.0, -1.0).y, -3.0, 1e-12);  // 2 k (y - axis), k = 3 / 4
}

TEST(StageSetup, RefusesA3DSceneAndATerrainFileItCannotRead) {
  test::RunoutWorld w({0, 0, 0}, {1, 1, 0}, 0.1);
  const int m = w.add_material("water", 1000.0, nullptr);
  w.fill_box({0, 0, 0}, {0.5, 0.5, 0}, m);
  w.world.dim = 3;
  expect_input_error([&] { w.make_stage(R"({"terrain": {"plane": {"slope": 0}}, "release_thickness": 1})", 1.0); },
                     {"dim", "plan view"});
  w.world.dim = 2;
  // Not a GeoTIFF: refused by GDAL, or by a build without GDAL; either way the message names the file and GDAL.
  const std::string tif = write_file("not_a_dem.tif", "hello");
  expect_input_error(
      [&] { w.make_stage(R"({"terrain": {"dem": {"file": ")" + tif + R"("}}, "release_thickness": 1})", 1.0); },
      {tif, "GDAL"});
  const std::string xyz = write_file("dem.xyz", "1 2 3");
  expect_input_error(
      [&] { w.make_stage(R"({"terrain": {"dem": {"file": ")" + xyz + R"("}}, "release_thickness": 1})", 1.0); },
      {"/terrain/dem/file", "allowed: .asc"});
  expect_input_error([&] { w.make_stage(R"({"terrain": {"plane": {"slope": 0}}})", 1.0); },
                     {"release_thickness"});
}

TEST(StageSetup, ReleaseFromAThicknessRasterDropsParticlesWithoutThickness) {
  // 1 m thick on the west half, no-data on the east half.
  const std::string path = write_file("release.asc",
                                      "ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 0.5\nNODATA_value -1\n"
                                      "1 -1\n1 -1\n");
  test::RunoutWorld w({0, 0, 0}, {1, 1, 0}, 0.1);
  const int m = w.add_material("water", 1000.0, nullptr);
  w.fill_box({0, 0, 0}, {1, 1, 0}, m);
  auto& stage = w.make_stage(R"({"terrain": {"plane": {"slope": 0}}, "thickness_raster": ")" + path + R"("})", 1.0);
  EXPECT_EQ(w.world.fluid.size(), 50u);
  EXPECT_NEAR(stage.total_volume(w.world), 50 * 0.01, 1e-12);
}

}  // namespace
}  // namespace talus::runout
