// The landslide chain on the planar slide through `talus run`: strength
// reduction hands the failed slab to run-out (rasters and a scene), the
// hand-off keeps the slab's volume within 1 %, and the generated run-out
// scene runs and keeps that volume exactly.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

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
