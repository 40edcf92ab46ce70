// Bad scenes found by the fuzzer (tools/fuzz_scenes.py), through the talus
// command with the shipped plugins: each is refused by `talus validate` with
// exit 2, an "error: " line naming the scene file and the JSON pointer, and
// `talus run` refuses it before it creates the output folder.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "process.hpp"

namespace fs = std::filesystem;
using nlohmann::json;
using talus::test::read_file;
using talus::test::run_command;
using talus::test::write_file;

namespace {

const std::string share = TALUS_SHARE_DIR;

json shipped(const std::string& name) { return json::parse(read_file(share + "/scenes/" + name + ".json")); }

struct Refusal {
  std::string scene, validate, run;
  int validate_code = -1, run_code = -1;
  bool wrote = false;
};

// Writes the scene as DIR/scene.json (beside a dem/ copy for runout scenes)
// and runs validate and run on it.
Refusal refuse(const std::string& name, const json& scene, const std::string& extra_file = {},
               const std::string& extra_text = {}) {
  const std::string dir = std::string(TALUS_BINARY_DIR) + "/tests/bad_scenes_" + name;
  fs::remove_all(dir);
  fs::create_directories(dir + "/scenes");
  fs::copy(share + "/dem", dir + "/dem");
  if (!extra_file.empty()) write_file(dir + "/" + extra_file, extra_text);
  Refusal r;
  r.scene = dir + "/scenes/scene.json";
  write_file(r.scene, scene.dump(1));
  const auto v = run_command(std::string(TALUS_EXE) + " validate " + r.scene);
  r.validate = v.output;
  r.validate_code = v.exit_code;
  const auto run = run_command(std::string(TALUS_EXE) + " run " + r.scene + " --quiet --out " + dir + "/out");
  r.run = run.output;
  r.run_code = run.exit_code;
  r.wrote = fs::exists(dir + "/out");
  return r;
}

void expect_refused(const Refusal& r, const std::string& pointer, const std::string& words) {
  const std::string head = "error: " + r.scene + ": " + pointer + ": ";
  EXPECT_EQ(r.validate_code, 2) << r.validate;
  EXPECT_EQ(r.validate.rfind(head, 0), 0u) << "expected to start with " << head << "\n" << r.validate;
  EXPECT_NE(r.validate.find(words), std::string::npos) << r.validate;
  EXPECT_EQ(r.run_code, 2) << r.run;
  EXPECT_EQ(r.run, r.validate);
  EXPECT_FALSE(r.wrote) << "run created its output folder";
}

// Narrower than the neighbour grid's 2.5 supports (2 x 7.5e-5 m): refused at
// the domain, not deep in the wcsph stage with neither file nor pointer.
TEST(BadScenes, PeriodicAxisNarrowerThanTheNeighbourSearch) {
  json s = shipped("poiseuille_2d");
  s["domain"]["max"][0] = 0.00015;
  s["bodies"][0]["shape"]["box"]["max"][0] = 0.00015;
  s["bodies"][1]["shape"]["box_walls"]["max"][0] = 0.00015;
  expect_refused(refuse("periodic", s), "/domain/periodic/0",
                 "the domain spans 0.00015 m along x, less than the 2.5 kernel supports a periodic axis needs (2.5 x "
                 "7.5e-05 m)");
}

// 2.7 supports: enough for wcsph and, since the neighbour grid reports every
// periodic image, for the probes too (their sampler once needed 3 supports
// and failed in `talus run` after the output folder was made).
TEST(BadScenes, ProbesRunOnAPeriodicAxisNarrowerThanThreeSupports) {
  json s = shipped("poiseuille_2d");
  s["domain"]["max"][0] = 0.0002;
  s["bodies"][0]["shape"]["box"]["max"][0] = 0.0002;
  s["bodies"][1]["shape"]["box_walls"]["max"][0] = 0.0002;
  s["time"]["end"] = 0.0005;
  s["outputs"] = json::array({{{"type", "probes"}, {"points", {{0.0001, 0.0005}}}}});
  const Refusal r = refuse("periodic_probes", s);
  EXPECT_EQ(r.validate_code, 0) << r.validate;
  EXPECT_EQ(r.run_code, 0) << r.run;
}

TEST(BadScenes, DomainWhoseExtentOverflows) {
  json s = shipped("poiseuille_2d");
  s["domain"]["min"][0] = -1e308;
  s["domain"]["max"][0] = 1e308;
  expect_refused(refuse("overflow", s), "/domain/max", "the extent along x, max - min, overflows a double");
}

TEST(BadScenes, SphStageWithoutAKernel) {
  json s = shipped("hydrostatic_2d");
  s.erase("kernel");
  s["outputs"] = json::array();
  expect_refused(refuse("no_kernel", s), "/pipeline/0", "the wcsph stage needs a smoothing kernel");
}

TEST(BadScenes, SmoothingLengthBeyondAKernelTable) {
  json s = shipped("hydrostatic_2d");
  s["kernel"]["h_over_dp"] = 0.5;
  for (auto& b : s["bodies"]) b["dp"] = 5e-324;  // h = 0.5 dp rounds to 0
  // The resource estimate sees it first: the particle count overflows.
  expect_refused(refuse("bad_h", s), "/bodies/0/dp", "more than can be counted");
}

TEST(BadScenes, AClumpWithAFixedBlockOrOnAFluidNamesTheJsonPointer) {
  json s = shipped("planar_slide");
  s["bodies"][0]["clump"] = "slope";
  s["bodies"][1]["clump"] = "slope";
  expect_refused(refuse("clump_fixed", s), "/bodies/0/clump", "block 'base' is fixed; a clump is a free body");
  json f = shipped("hydrostatic_2d");
  f["bodies"][0]["clump"] = "water";
  expect_refused(refuse("clump_fluid", f), "/bodies/0/clump", "does not apply to a fluid body");
}

TEST(BadScenes, UnknownOutputField) {
  json s = shipped("hydrostatic_2d");
  s["outputs"][1]["fields"] = {"velocity", "vorticity"};  // after the probes, which used to open their CSV first
  expect_refused(refuse("fields", s), "/outputs/1/fields", "no particle field 'vorticity'");
}

TEST(BadScenes, WaveGaugeOutsideTheDomain) {
  json s = shipped("hydrostatic_2d");
  s["outputs"][0]["gauges"] = {{0.9, 0.1}};
  expect_refused(refuse("gauge", s), "/outputs/0/gauges", "G1 at (0.9, 0.1) is outside the domain");
}

TEST(BadScenes, MeshErrorNamesTheJsonPointer) {
  json s = shipped("hydrostatic_2d");
  s["bodies"][0]["shape"] = {{"mesh", {{"file", "../bad.obj"}}}};
  const std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n";
  expect_refused(refuse("mesh", s, "bad.obj", obj), "/bodies/0/shape/mesh/file",
                 "bad.obj:4: face refers to vertex 4 but only 3 vertices are defined so far");
}

TEST(BadScenes, AWallMeshWithAFlippedTriangleNamesTheJsonPointer) {
  json s = shipped("hydrostatic_2d");
  s["bodies"][1]["shape"] = {{"mesh", {{"file", "../flipped.obj"}}}};
  const std::string obj = "v 0 0 -1\nv 1 0 -1\nv 1 1 -1\nv 0 1 -1\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
                          "f 1 4 3 2\nf 8 7 6 5\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";
  expect_refused(refuse("flipped_mesh", s, "flipped.obj", obj), "/bodies/1/shape/mesh/file", "is flipped");
}

TEST(BadScenes, FreeSlipOnAWallModelWithoutNormalsNamesTheJsonPointer) {
  json s = shipped("hydrostatic_2d");
  s["bodies"][1]["boundary"]["slip"] = "free_slip";  // dynamic_particles, method dbc
  expect_refused(refuse("free_slip_dbc", s), "/bodies/1/boundary/slip", "free_slip needs \"method\": \"mdbc\"");
}

TEST(BadScenes, DemErrorNamesTheJsonPointer) {
  json s = shipped("runout_valley");
  s["pipeline"][0]["terrain"]["dem"]["file"] = "../bad.asc";
  expect_refused(refuse("dem", s, "bad.asc", "ncols 120\nnrows 80\n"), "/pipeline/0/terrain/dem/file",
                 "bad.asc: header has no");
}

TEST(BadScenes, PluginThatCannotBeLoadedHasOneErrorPrefix) {
  json s = shipped("hydrostatic_2d");
  s["plugins"] = {"nowhere"};
  const Refusal r = refuse("plugin", s);
  expect_refused(r, "/plugins/0", "plugin '");
  EXPECT_EQ(r.validate.find("error: ", 7), std::string::npos) << r.validate;
}

TEST(BadScenes, AFluidBodyOutsideTheDomain) {
  // The run dropped the particles outside only at the first step, after building neighbour grids for them.
  json s = shipped("sediment_bank_2d");
  s["bodies"][15]["shape"] = {{"box", {{"min", {0, 0}}, {"max", {17.5, 4}}}}};
  expect_refused(refuse("outside_domain", s), "/bodies/15/shape", "380590 of 383616 particles lie outside the domain (-0.06, 0) .. (1.202, 0.459)");
}

TEST(BadScenes, ABlowUpDuringTheRunEndsWithAnErrorLine) {
  // Valid input that cannot be integrated: the block leaves with a non-finite position at the first step.
  json s = shipped("buoyancy_floating");
  s["gravity"][2] = -1e308;
  s["time"]["max_steps"] = 3;
  const Refusal r = refuse("blow_up", s);
  EXPECT_EQ(r.validate_code, 0) << r.validate;
  EXPECT_EQ(r.run_code, 1) << r.run;
  EXPECT_EQ(r.run.rfind("error: step 0 (t = 0 s): block 'box' has a non-finite position", 0), 0u) << r.run;
}

TEST(BadScenes, AnEndTimeOf1e308KeepsOutputsAndCheckpointsOnTheirIntervals) {
  // The tolerance for "due" once scaled with the end time: every step was due and the schedule never advanced.
  json s = shipped("poiseuille_2d");
  s["time"]["end"] = 1e308;
  s["time"]["max_steps"] = 3;
  s["checkpoint"] = {{"every", 1e-3}};
  const std::string dir = std::string(TALUS_BINARY_DIR) + "/tests/bad_scenes_end_1e308";
  fs::remove_all(dir);
  fs::create_directories(dir);
  write_file(dir + "/scene.json", s.dump(1));
  const auto r = run_command("timeout 120 " + std::string(TALUS_EXE) + " run " + dir + "/scene.json --quiet --out " + dir + "/out");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(fs::exists(dir + "/out/scene.h5part"));
}

}  // namespace
