// End to end through the host: the shipped real-terrain scene runs, writes
// its rasters, and keeps the released volume.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "esri_ascii.hpp"

namespace talus::runout {
namespace {

namespace fs = std::filesystem;

TEST(RunoutScene, ValleySceneRunsAndWritesItsRasters) {
  const fs::path dir = fs::temp_directory_path() / "talus_runout_scene";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string cmd = "cd '" + dir.string() + "' && '" + TALUS_EXE + "' run '" + TALUS_SHARE_DIR +
                          "/scenes/runout_valley.json' --out out > log.txt 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << std::ifstream(dir / "log.txt").rdbuf();
  std::stringstream log;
  log << std::ifstream(dir / "log.txt").rdbuf();
  EXPECT_NE(log.str().find("deposit volume"), std::string::npos) << log.str();
  for (const char* name : {"peak_thickness", "peak_velocity", "deposit_thickness", "arrival_time", "elevation"})
    ASSERT_TRUE(fs::exists(dir / "out" / (std::string("runout_valley_") + name + ".asc"))) << name;
  const Grid deposit = read_esri_ascii((dir / "out" / "runout_valley_deposit_thickness.asc").string(), true);
  const Grid z = read_esri_ascii((dir / "out" / "runout_valley_elevation.asc").string());
  const Grid dem = read_esri_ascii(std::string(TALUS_SHARE_DIR) + "/dem/runout_valley.asc");
  EXPECT_EQ(deposit.ncols, dem.ncols);
  EXPECT_EQ(deposit.nrows, dem.nrows);
  // The mass left the release area (x < 90 m) and came to rest down-slope.
  double far = 0.0, total = 0.0;
  for (int r = 0; r < deposit.nrows; ++r)
    for (int c = 0; c < deposit.ncols; ++c) {
      total += deposit.at(c, r);
      if (deposit.x_of(c) > 150.0) far += deposit.at(c, r);
    }
  EXPECT_GT(far, 0.9 * total);
  EXPECT_NEAR(z.at(10, 10), dem.at(10, 10), 1e-3);
}

}  // namespace
}  // namespace talus::runout
