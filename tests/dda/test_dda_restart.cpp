// A DDA run continued from a checkpoint ends bit for bit where the
// uninterrupted run ends: contact history, angular momenta and the leapfrog
// state travel in the stage's checkpoint state; a clump's state follows from
// its blocks'.
#include <gtest/gtest.h>

#include <algorithm>

#include <filesystem>

#include <nlohmann/json.hpp>

#include "process.hpp"

namespace fs = std::filesystem;
using talus::test::read_file;
using talus::test::run_command;

namespace {

// Runs `scene` (JSON text) to its end with a checkpoint every 0.1 s, then
// again from the first checkpoint; true when both end in the same bytes.
void expect_restart_bit_for_bit(const std::string& name, const std::string& scene) {
  const std::string dir = std::string(TALUS_BINARY_DIR) + "/tests/dda_restart_" + name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string path = dir + "/scene.json";
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

nlohmann::json incline() {
  auto s = nlohmann::json::parse(read_file(std::string(TALUS_SHARE_DIR) + "/scenes/block_on_incline.json"));
  s["time"] = {{"end", 0.2}};
  s["checkpoint"] = {{"every", 0.1}, {"keep", 5}};
  return s;
}

}  // namespace

TEST(DdaRestart, BlockOnInclineContinuesBitForBit) { expect_restart_bit_for_bit("incline", incline().dump()); }

TEST(DdaRestart, AClumpContinuesBitForBit) {
  // The cube and a copy of it 0.3 m higher and 0.1 m down the slope, one
  // clump: an uneven body that slides and turns.
  nlohmann::json s = incline();
  nlohmann::json top = s["bodies"][1];
  top["name"] = "top";
  for (auto& v : top["shape"]["polyhedron"]["vertices"]) {
    v[0] = v[0].get<double>() + 0.1;
    v[2] = v[2].get<double>() + 0.3;
  }
  s["bodies"][1]["clump"] = "body";
  top["clump"] = "body";
  s["bodies"].push_back(top);
  expect_restart_bit_for_bit("clump", s.dump());
}
