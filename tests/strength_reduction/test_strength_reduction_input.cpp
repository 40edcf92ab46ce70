// Bad strength-reduction scenes are refused before anything is written, with
// the JSON path (exit 2); a bracket that misses F_s ends the run with exit 1,
// says which end to move, and keeps the trial table.
#include <gtest/gtest.h>

#include <filesystem>

#include "planar_slide_scene.hpp"

namespace fs = std::filesystem;
using namespace talus::test;

namespace {

void expect_refused(const nlohmann::json& scene, const std::string& name, const std::string& where,
                    const std::string& what) {
  const FactorRun r = run_scene(scene, name);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find(where), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(what), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(r.directory)) << "an output folder was created for a refused scene";
}

nlohmann::json& slab(nlohmann::json& scene) { return scene["bodies"][1]; }

void shift_slab(nlohmann::json& scene, double dx, double dz) {
  for (auto& v : slab(scene)["shape"]["polyhedron"]["vertices"]) {
    v[0] = v[0].get<double>() + dx;
    v[2] = v[2].get<double>() + dz;
  }
}

}  // namespace

TEST(StrengthReductionInput, BadParametersNameTheirPath) {
  nlohmann::json s = planar_slide({});
  s["pipeline"][0]["bracket"] = {2.0, 1.0};
  expect_refused(s, "bad_bracket", "/pipeline/0/bracket", "needs 0 < lo < hi");
  s = planar_slide({});
  s["pipeline"][0]["tolerance"] = 5.0;
  expect_refused(s, "bad_tolerance", "/pipeline/0/tolerance", "smaller than the bracket");
  s = planar_slide({});
  s["pipeline"][0]["monitors"] = {{100.0, 2.0, 0.0}};
  expect_refused(s, "monitor_outside", "/pipeline/0/monitors/0", "outside every block");
  s = planar_slide({});
  s["pipeline"][0]["monitors"] = {{0.0, 2.0, -2.0}};
  expect_refused(s, "monitor_in_base", "/pipeline/0/monitors/0", "fixed block 'base'");
  s = planar_slide({});
  s["pipeline"][0]["file"] = "../escape";
  expect_refused(s, "file_outside", "/pipeline/0/file", "");
}

TEST(StrengthReductionInput, SlopesThatCannotBeReducedAreRefused) {
  nlohmann::json s = planar_slide({});
  shift_slab(s, 0.0, 2.0);  // lifted off its base
  expect_refused(s, "no_joints", "/pipeline/0", "no joints");
  s = planar_slide({});
  shift_slab(s, 0.0, -0.5);  // sunk into its base
  expect_refused(s, "overlap", "/bodies/1/shape", "overlap by");
  s = planar_slide({});
  s["pipeline"].push_back({{"stage", "dda"}});
  expect_refused(s, "with_dda", "/pipeline/1: stage 'dda' builds the blocks that stage 'strength_reduction'", "list only one");
  s = planar_slide({});
  s["gravity"] = {0.0, 0.0, 0.0};
  expect_refused(s, "no_gravity", "/pipeline/0", "no gravity");
  s = planar_slide({});
  s["bodies"][0]["fixed"] = false;
  s["bodies"].push_back(s["bodies"][0]);  // a second loose block far away
  s["bodies"][2]["name"] = "loose";
  for (auto& v : s["bodies"][2]["shape"]["polyhedron"]["vertices"]) v[1] = v[1].get<double>() + 8.0;
  s["bodies"][0]["fixed"] = true;
  s["domain"]["max"][1] = 20.0;
  expect_refused(s, "loose_block", "/bodies/2/shape", "touches no other block");
}

TEST(StrengthReductionInput, ABracketThatMissesTheFactorSaysWhichEndToMove) {
  nlohmann::json s = planar_slide({});  // F = 1.1201
  s["pipeline"][0]["bracket"] = {1.5, 4.0};
  FactorRun r = run_scene(s, "fails_at_lower");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("fails already at F = 1.5000"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("/pipeline/0/bracket/0"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(r.directory + "/strength_reduction.csv"));
  s["pipeline"][0]["bracket"] = {0.5, 1.0};
  r = run_scene(s, "holds_at_upper");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("still holds at F = 1.0000"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("/pipeline/0/bracket/1"), std::string::npos) << r.output;
}

TEST(StrengthReductionInput, APackOfBlocksOnLevelGroundHoldsAtEveryFactor) {
  // Four 2.5 m prisms packed 2 x 2 on a level floor cannot fail: every trial must reach equilibrium. Coincident
  // faces once clipped to 4 or 8 points and relabelled them from step to step, resetting the springs, and the
  // pack chattered without end (the gravity-loaded state or the first trial never came to rest).
  nlohmann::json s = planar_slide({});
  // Away from the origin, where the face planes' offsets carry rounding errors of a few 1e-15 m.
  s["bodies"] = {prism_block("floor", {{-25, -10}, {30, -10}, {30, 0}, {-25, 0}}, true)};
  for (int i = 0; i < 2; ++i)
    for (int k = 0; k < 2; ++k) {
      const double x = -15.0 + 2.5 * i, z = 2.5 * k;
      s["bodies"].push_back(prism_block("b" + std::to_string(i) + std::to_string(k),
                                        {{x, z}, {x + 2.5, z}, {x + 2.5, z + 2.5}, {x, z + 2.5}}, false));
    }
  s["pipeline"][0].erase("monitors");
  const FactorRun r = run_scene(s, "pack");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("still holds at F = 4.0000"), std::string::npos) << r.output;
}
