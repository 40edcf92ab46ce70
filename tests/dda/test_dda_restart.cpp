// A DDA run continued from a checkpoint ends bit for bit where the
// uninterrupted run ends: contact history, angular momenta and the leapfrog
// state travel in the stage's checkpoint state.
#include <gtest/gtest.h>

#include <algorithm>

#include <filesystem>

#include "process.hpp"

namespace fs = std::filesystem;
using talus::test::read_file;
using talus::test::run_command;

TEST(DdaRestart, BlockOnInclineContinuesBitForBit) {
  const std::string dir = std::string(TALUS_BINARY_DIR) + "/tests/dda_restart";
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::string scene = read_file(std::string(TALUS_SHARE_DIR) + "/scenes/block_on_incline.json");
  const auto time = scene.find("\"time\": {\"end\": 1.0}");
  ASSERT_NE(time, std::string::npos);
  scene.replace(time, 20, "\"time\": {\"end\": 0.2}, \"checkpoint\": {\"every\": 0.1, \"keep\": 5}");
  const std::string path = dir + "/incline.json";
  talus::test::write_file(path, scene);
  const std::string exe = TALUS_EXE;
  ASSERT_EQ(run_command(exe + " run " + path + " --quiet --out " + dir + "/a").exit_code, 0);
  std::vector<fs::path> checkpoints;
  for (const auto& e : fs::directory_iterator(dir + "/a"))
    if (e.path().extension() == ".checkpoint") checkpoints.push_back(e.path());
  std::sort(checkpoints.begin(), checkpoints.end());
  ASSERT_EQ(checkpoints.size(), 2u);
  const auto resumed = run_command(exe + " run " + path + " --quiet --out " + dir + "/b --restart " +
                                   checkpoints.front().string());
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  const fs::path end_b = fs::path(dir) / "b" / checkpoints.back().filename();
  ASSERT_TRUE(fs::exists(end_b));
  EXPECT_TRUE(read_file(checkpoints.back().string()) == read_file(end_b.string()))
      << "the restarted DDA run differs from the uninterrupted one";
}
