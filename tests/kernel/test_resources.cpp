// A scene too large for the machine is refused before anything is allocated,
// naming the JSON pointer that drives its size (exit 2, nothing written),
// unless --allow-large; the estimate behind it matches the particles a scene
// makes; an allocation that still fails ends with a clear message.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "plugin_registry.hpp"
#include "process.hpp"
#include "resource_estimate.hpp"
#include "scene.hpp"
#include "simulation.hpp"
#include "talus/error.hpp"
#include "talus/memory.hpp"
#include "talus/world.hpp"

namespace fs = std::filesystem;
using nlohmann::json;
using talus::test::run_command;
using talus::test::write_file;

namespace {

const std::string exe = std::string("TALUS_PLUGIN_PATH=") + TALUS_TEST_PLUGINS + "/good " + TALUS_EXE;

std::string scratch(const std::string& name) {
  const fs::path dir = fs::path(TALUS_BINARY_DIR) / "tests" / "resources_scratch" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir.string();
}

json read_json(const std::string& path) {
  std::ifstream in(path);
  return json::parse(in);
}

std::string write_scene(const json& scene, const std::string& dir) {
  const std::string path = dir + "/scene.json";
  write_file(path, scene.dump(1));
  return path;
}

json ballistic() { return read_json(std::string(TALUS_TEST_SCENES) + "/ballistic.json"); }

TEST(Memory, AvailableMemoryAndItsText) {
  EXPECT_GT(talus::available_memory(), 1u << 20);
  EXPECT_EQ(talus::memory_text(512), "512 bytes");
  EXPECT_EQ(talus::memory_text(1.5 * 1024 * 1024 * 1024), "1.5 GiB");
}

TEST(Memory, RequireMemoryRefusesUnlessAllowed) {
  try {
    talus::require_memory(1e30, "scene.json: /bodies/0/dp", "the scene");
    FAIL() << "expected an InputError";
  } catch (const talus::InputError& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.rfind("error: scene.json: /bodies/0/dp: the scene needs about ", 0), 0u) << m;
    EXPECT_NE(m.find("--allow-large"), std::string::npos) << m;
  }
  EXPECT_NO_THROW(talus::require_memory(1e3, "scene.json", "the scene"));
  talus::set_memory_check(false);
  EXPECT_NO_THROW(talus::require_memory(1e30, "scene.json", "the scene"));
  talus::set_memory_check(true);
}

// The estimate (from the scene alone) against the particles the scene makes:
// close, or above by at most `over` where the scene removes some after making
// them (fluid in a block's place) or covers only some faces of a block.
void expect_estimate_close(const std::string& scene_path, double tolerance, double over = 1.0) {
  talus::PluginRegistry registry;
  registry.add_default_locations();
  talus::Scene scene = talus::load_scene(scene_path, registry);
  const talus::ResourceEstimate e = talus::estimate_resources(scene, registry);
  talus::Simulation sim(registry, std::move(scene));
  const double fluid = static_cast<double>(sim.world().fluid.size());
  const double walls = static_cast<double>(sim.world().boundary.size());
  EXPECT_GE(e.fluid_particles, (1.0 - tolerance) * fluid) << scene_path;
  EXPECT_LE(e.fluid_particles, over * (1.0 + tolerance) * fluid) << scene_path;
  EXPECT_GE(e.wall_particles, (1.0 - tolerance) * walls) << scene_path;
  EXPECT_LE(e.wall_particles, over * (1.0 + tolerance) * walls) << scene_path;
}

TEST(Estimate, MatchesTheParticlesScenesMake) {
  expect_estimate_close(std::string(TALUS_SOURCE_DIR) + "/tests/verification/water_drop_2d.json", 0.01);
  expect_estimate_close(std::string(TALUS_SHARE_DIR) + "/scenes/dam_break_3d.json", 0.01);
  expect_estimate_close(std::string(TALUS_SHARE_DIR) + "/scenes/block_impact.json", 0.01, 3.0);
  expect_estimate_close(std::string(TALUS_SHARE_DIR) + "/scenes/sediment_bank_2d.json", 0.05);
}

TEST(Estimate, CurvedAndHalfSpaceShapes) {
  const std::string dir = scratch("shapes");
  json scene = read_json(std::string(TALUS_SOURCE_DIR) + "/tests/verification/water_drop_2d.json");
  scene["bodies"][0]["shape"] = {{"sphere", {{"centre", {0.1, 0.15}}, {"radius", 0.05}}}};
  expect_estimate_close(write_scene(scene, dir), 0.05);
  scene["bodies"][0]["shape"] = {{"half_space", {{"point", {0.0, 0.1}}, {"normal", {0.0, 1.0}}}}};
  expect_estimate_close(write_scene(scene, dir), 0.05);
  scene["bodies"][0]["shape"] = {{"polygon", {{"vertices", {{0.02, 0.05}, {0.18, 0.05}, {0.1, 0.2}}}}}};
  expect_estimate_close(write_scene(scene, dir), 0.05);
}

TEST(Estimate, AMeshInA2dSceneCountsItsSectionNotItsVolume) {
  // A slab 2 mm thick in z: the 2D lattice is its section, 0.16 m by 0.15 m, whatever its volume.
  const std::string dir = scratch("mesh_2d");
  write_file(dir + "/slab.obj",
             "v 0.02 0.05 -0.001\nv 0.18 0.05 -0.001\nv 0.18 0.2 -0.001\nv 0.02 0.2 -0.001\n"
             "v 0.02 0.05 0.001\nv 0.18 0.05 0.001\nv 0.18 0.2 0.001\nv 0.02 0.2 0.001\n"
             "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n");
  json scene = read_json(std::string(TALUS_SOURCE_DIR) + "/tests/verification/water_drop_2d.json");
  scene["bodies"][0]["shape"] = {{"mesh", {{"file", "slab.obj"}}}};
  expect_estimate_close(write_scene(scene, dir), 0.1);
}

TEST(Estimate, PlanPrintsParticlesMemoryAndSteps) {
  const std::string dir = scratch("plan");
  const auto r = run_command(exe + " plan " + write_scene(ballistic(), dir));
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("estimate (before allocating):\n  fluid 'drop': 100 particles"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("  memory: about "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("  steps: 100  (/pipeline/0/dt)"), std::string::npos) << r.output;
}

// Refused in well under the time it would take to make the particles.
void expect_refused_quickly(const std::string& command, const std::string& file, const std::string& pointer,
                            const std::string& out) {
  const auto start = std::chrono::steady_clock::now();
  const auto r = run_command(command);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("error: " + file + ": " + pointer + ": the scene ("), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("of memory; this machine has "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("--allow-large"), std::string::npos) << r.output;
  EXPECT_LT(seconds, 20.0);
  if (!out.empty()) EXPECT_FALSE(fs::exists(out)) << out;
}

TEST(Refusal, AFineDpIsRefusedBeforeAllocatingNamingItsPointer) {
  const std::string dir = scratch("fine_dp");
  json scene = ballistic();
  scene["bodies"][0]["dp"] = 1e-7;  // 2.5e13 particles
  const std::string path = write_scene(scene, dir);
  expect_refused_quickly(exe + " run " + path + " --quiet --out " + dir + "/out", path, "/bodies/0/dp", dir + "/out");
  expect_refused_quickly(exe + " validate " + path, path, "/bodies/0/dp", "");
  const auto plan = run_command(exe + " plan " + path);
  EXPECT_EQ(plan.exit_code, 2);
  EXPECT_NE(plan.output.find("fluid 'drop': 2.5e+13 particles"), std::string::npos) << plan.output;
}

TEST(Refusal, TheDefaultSceneAtAFineDpIsRefused) {
  const std::string dir = scratch("default_fine");
  json scene = read_json(std::string(TALUS_SHARE_DIR) + "/scenes/block_impact.json");
  for (auto& b : scene["bodies"])
    if (b.contains("dp")) b["dp"] = 1e-4;
  const std::string path = write_scene(scene, dir);
  expect_refused_quickly(std::string(TALUS_EXE) + " run " + path + " --quiet --out " + dir + "/out", path,
                         "/bodies/0/dp", dir + "/out");
}

TEST(Refusal, AHugeDomainIsRefusedNamingIt) {
  const std::string dir = scratch("huge_domain");
  json scene = read_json(std::string(TALUS_SOURCE_DIR) + "/tests/verification/water_drop_2d.json");
  scene["domain"]["max"] = {1e7, 1e7};
  const std::string path = write_scene(scene, dir);
  expect_refused_quickly(std::string(TALUS_EXE) + " run " + path + " --quiet --out " + dir + "/out", path, "/domain",
                         dir + "/out");
}

TEST(Refusal, AnAddressSpaceLimitCountsAsTheMemoryAvailable) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "AddressSanitizer reserves its shadow memory beyond any ulimit -v: it cannot start under one";
#endif
  // 4e6 particles, about 2.2 GiB by the estimate: within this machine, not within `ulimit -v` of 1.5 GiB.
  const std::string dir = scratch("ulimit");
  json scene = ballistic();
  scene["bodies"][0]["dp"] = 2.5e-4;
  const std::string path = write_scene(scene, dir);
  expect_refused_quickly("ulimit -v 1500000 && " + exe + " run " + path + " --quiet --out " + dir + "/out", path,
                         "/bodies/0/dp", dir + "/out");
}

TEST(Refusal, AllowLargeLetsASceneThroughTheEstimate) {
  // A scene the estimate refuses only because the machine is small would run with
  // --allow-large; here one that allocates nothing large shows the option is accepted
  // by every command and turns no check of the scene itself off.
  const std::string dir = scratch("allow_large");
  const std::string path = write_scene(ballistic(), dir);
  EXPECT_EQ(run_command(exe + " validate " + path + " --allow-large").exit_code, 0);
  EXPECT_EQ(run_command(exe + " plan " + path + " --allow-large").exit_code, 0);
  EXPECT_EQ(run_command(exe + " run " + path + " --quiet --allow-large --out " + dir + "/out").exit_code, 0);
  const auto help = run_command(exe + " --help");
  EXPECT_NE(help.output.find("--allow-large"), std::string::npos) << help.output;
}

// An allocation that fails anyway (past the estimate, or with --allow-large)
// ends with a message and exit 2, not a crash or a bare "std::bad_alloc".
TEST(Refusal, AFailedAllocationEndsWithAClearMessage) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "AddressSanitizer's operator new reports a failed allocation itself instead of throwing "
                  "std::bad_alloc (the fuzz gate counts that report as out of memory)";
#endif
  const std::string dir = scratch("bad_alloc");
  json scene = ballistic();
  scene["pipeline"][0]["scratch_bytes"] = 4.6e18;  // beyond any address space: fails at once
  auto r = run_command(exe + " run " + write_scene(scene, dir) + " --quiet --out " + dir + "/out");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_EQ(r.output.rfind("error: talus run: out of memory (std::bad_alloc): ", 0), 0u) << r.output;
  scene["pipeline"][0]["scratch_bytes"] = 1e19;  // beyond vector::max_size
  r = run_command(exe + " validate " + write_scene(scene, dir));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_EQ(r.output.rfind("error: talus validate: a size beyond what this machine can hold (std::length_error: ", 0), 0u)
      << r.output;
}

}  // namespace
