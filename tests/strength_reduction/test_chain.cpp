// The landslide chain through `talus run`, on the planar slide and on the
// hillside DEM's ellipsoidal slide: strength reduction hands the failed mass
// to run-out (rasters and a scene), the hand-off keeps its volume within 1 %,
// the terrain is the DEM with the slip surface let into it, and the generated
// run-out scene runs and keeps the volume exactly.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <sstream>
#include <vector>

#include "planar_slide_scene.hpp"
#include "process.hpp"

namespace fs = std::filesystem;
using namespace talus::test;

namespace {

nlohmann::json chain_scene() {
  nlohmann::json s = planar_slide({});
  s["pipeline"][0]["handoff"] = {{"runout_scene", TALUS_SHARE_DIR "/scenes/planar_slide_runout.json"},
                                 {"dem", TALUS_SHARE_DIR "/dem/planar_slide_valley.asc"}};
  return s;
}

// Values of an ESRI ASCII grid (six header lines), row by row.
std::vector<double> raster(const std::string& path) {
  std::istringstream in(read_file(path));
  std::string line;
  for (int k = 0; k < 6; ++k) std::getline(in, line);
  std::vector<double> v;
  for (double x; in >> x;) v.push_back(x);
  return v;
}

double number_after(const std::string& text, const std::string& key) {
  const auto at = text.find(key);
  return at == std::string::npos ? -1.0 : std::atof(text.c_str() + at + key.size());
}

}  // namespace

TEST(LandslideChain, TheFailedSlabRunsOutWithItsVolume) {
  const FactorRun sr = run_scene(chain_scene(), "chain", "");
  ASSERT_EQ(sr.exit_code, 0) << sr.output;
  for (const char* f : {"_terrain.asc", "_thickness.asc", "_basal_shear.asc", "_runout.json"})
    EXPECT_TRUE(fs::exists(sr.directory + "/strength_reduction" + f)) << f;
  const std::string summary = read_file(sr.directory + ".summary.json");
  const double slab = 20.0 * 4.0 * 8.660254037844386;
  const double released = number_after(summary, "released volume ");
  const double raster = number_after(summary, "in the thickness raster ");
  std::printf("hand-off: slab %.2f m^3, released %.3f m^3, raster %.3f m^3\n", slab, released, raster);
  EXPECT_NEAR(released / slab, 1.0, 1e-5);  // printed to 6 digits
  EXPECT_NEAR(raster / slab, 1.0, 0.01);
  EXPECT_NE(summary.find("basal shear from 4 slip-surface contacts"), std::string::npos) << summary;

  const std::string runout = sr.directory + "/strength_reduction_runout.json";
  const auto scene = nlohmann::json::parse(read_file(runout));
  // The reduced strength at F_s (printed to 4 decimals in the summary).
  EXPECT_NEAR(scene["materials"]["slide"]["rheology"]["yield_stress"].get<double>() * sr.safety_factor / 1e4, 1.0, 1e-4);
  EXPECT_NEAR(scene["materials"]["slide"]["rheology"]["basal_friction_angle"].get<double>(),
              std::atan(std::tan(M_PI / 6.0) / sr.safety_factor) * 180.0 / M_PI, 1e-2);
  const std::string out = sr.directory + "_runout";
  fs::remove_all(out);
  const auto ro = run_command(std::string(TALUS_EXE) + " run " + runout + " --quiet --out " + out + " --summary " +
                              out + ".summary.json");
  ASSERT_EQ(ro.exit_code, 0) << ro.output;
  const std::string ro_summary = read_file(out + ".summary.json");
  const double deposit = number_after(ro_summary, "deposit volume ");
  EXPECT_NEAR(deposit / raster, 1.0, 1e-5) << ro_summary;
}

TEST(LandslideChain, TheBasalShearInterpolationIsTheScenes) {
  nlohmann::json s = chain_scene();
  s["pipeline"][0]["handoff"]["basal_shear"] = "inverse_distance_linear";
  const FactorRun sr = run_scene(s, "chain_linear", "");
  ASSERT_EQ(sr.exit_code, 0) << sr.output;
  const std::string summary = read_file(sr.directory + ".summary.json");
  EXPECT_NE(summary.find("basal shear from 4 slip-surface contacts (inverse distance, linear nodal functions)"),
            std::string::npos) << summary;
}

TEST(LandslideChain, ABadHandoffIsRefusedBeforeAnythingIsWritten) {
  nlohmann::json s = chain_scene();
  s["pipeline"][0]["handoff"].erase("dem");
  FactorRun r = run_scene(s, "chain_no_cell");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("/pipeline/0/handoff/cell"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(r.directory));
  s = chain_scene();
  s["pipeline"][0]["handoff"]["runout_scene"] = TALUS_SHARE_DIR "/scenes/runout_valley.json";  // a Voellmy law
  r = run_scene(s, "chain_not_bingham");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("/materials/debris/rheology"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(r.directory));
}

TEST(LandslideChain, TheHillsideSlideRunsOutOverItsDem) {
  nlohmann::json s = nlohmann::json::parse(read_file(TALUS_SHARE_DIR "/scenes/hillside_chain.json"));
  s["pipeline"][0]["handoff"] = {{"runout_scene", TALUS_SHARE_DIR "/scenes/hillside_runout.json"},
                                 {"dem", TALUS_SHARE_DIR "/dem/hillside_valley.asc"}};
  const FactorRun sr = run_scene(s, "hillside_chain", "");
  ASSERT_EQ(sr.exit_code, 0) << sr.output;
  std::printf("hillside: F_s = %.4f in [%.4f, %.4f]\n", sr.safety_factor, sr.holds, sr.fails);
  const std::string summary = read_file(sr.directory + ".summary.json");
  const std::string description = s["description"];
  const double block = number_after(description, "the ellipsoidal cap ");
  const double released = number_after(summary, "released volume ");
  const double in_raster = number_after(summary, "in the thickness raster ");
  std::printf("hillside hand-off: block %.1f m^3, released %.1f m^3, raster %.1f m^3\n", block, released, in_raster);
  EXPECT_NEAR(released / block, 1.0, 1e-5);
  EXPECT_NEAR(in_raster / block, 1.0, 0.01);

  // The terrain: the DEM where nothing failed, the slip surface under the failed mass, never above the DEM.
  const auto dem = raster(TALUS_SHARE_DIR "/dem/hillside_valley.asc");
  const auto terrain = raster(sr.directory + "/strength_reduction_terrain.asc");
  const auto thickness = raster(sr.directory + "/strength_reduction_thickness.asc");
  ASSERT_EQ(terrain.size(), dem.size());
  ASSERT_EQ(thickness.size(), dem.size());
  std::size_t failed = 0;
  double deepest = 0.0;
  for (std::size_t k = 0; k < dem.size(); ++k) {
    EXPECT_LE(terrain[k], dem[k] + 1e-6) << "cell " << k;
    if (thickness[k] > 0.0) {
      ++failed;
      deepest = std::max(deepest, dem[k] - terrain[k]);
    }
  }
  std::printf("hillside: %zu failed cells, slip surface up to %.2f m under the DEM\n", failed, deepest);
  EXPECT_GT(failed, 100u);
  EXPECT_GT(deepest, 5.0);

  const std::string runout = sr.directory + "/strength_reduction_runout.json";
  const std::string out = sr.directory + "_runout";
  fs::remove_all(out);
  const auto ro = run_command(std::string(TALUS_EXE) + " run " + runout + " --quiet --out " + out + " --summary " +
                              out + ".summary.json");
  ASSERT_EQ(ro.exit_code, 0) << ro.output;
  const double deposit = number_after(read_file(out + ".summary.json"), "deposit volume ");
  EXPECT_NEAR(deposit / in_raster, 1.0, 1e-5);
}
