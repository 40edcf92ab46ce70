// The `talus` command end to end with a test stage: exit codes, pinned
// messages, nothing written on bad input, restart bit for bit, SIGINT.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <thread>
#include <vector>

#include "process.hpp"
#include "talus/build_info.hpp"

namespace fs = std::filesystem;
using talus::test::read_file;
using talus::test::run_command;

namespace {

const std::string exe = std::string("TALUS_PLUGIN_PATH=") + TALUS_TEST_PLUGINS + "/good " + TALUS_EXE;
const std::string scenes = TALUS_TEST_SCENES;

std::string fresh_dir(const std::string& name) {
  const std::string dir = std::string(TALUS_BINARY_DIR) + "/tests/cli_" + name;
  fs::remove_all(dir);
  return dir;
}

// The run of `scene` in `a` wrote checkpoints: restarted in `b` from the first, it must end on
// the same bytes as the last.
void expect_restart_ends_on_the_same_checkpoint(const std::string& scene, const std::string& a, const std::string& b) {
  std::vector<fs::path> checkpoints;
  for (const auto& e : fs::directory_iterator(a))
    if (e.path().extension() == ".checkpoint") checkpoints.push_back(e.path());
  std::sort(checkpoints.begin(), checkpoints.end());
  ASSERT_GE(checkpoints.size(), 2u);
  const auto resumed = run_command(std::string(TALUS_EXE) + " run " + scene + " --quiet --threads 1 --out " + b +
                                   " --restart " + checkpoints.front().string());
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  const fs::path end_b = fs::path(b) / checkpoints.back().filename();
  ASSERT_TRUE(fs::exists(end_b)) << end_b;
  EXPECT_TRUE(read_file(checkpoints.back().string()) == read_file(end_b.string()))
      << "the run restarted from " << checkpoints.front() << " differs from the uninterrupted one";
}

TEST(Cli, HelpAndVersion) {
  EXPECT_EQ(run_command(exe + " --version").exit_code, 0);
  const auto help = run_command(exe + " --help");
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_NE(help.output.find("talus COMMAND"), std::string::npos);
  EXPECT_EQ(run_command(exe + " frobnicate").exit_code, 2);
}

TEST(Cli, ValidateReportsAllThreeErrorsAndWritesNothing) {
  const std::string out = fresh_dir("three_errors");
  const auto r = run_command("cd " + std::string(TALUS_BINARY_DIR) + " && " + exe + " run " + scenes +
                             "/three_errors.json --out " + out);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  const std::string file = scenes + "/three_errors.json";
  EXPECT_EQ(r.output,
            "error: " + file + ": /bodies/0/dp: expected a number, got the string \"fine\"\n"
            "error: " + file + ": /pipeline/0/dt: -0.001 is out of range; must be > 0\n"
            "error: " + file + ": /time/resort_evry: unknown parameter in time\n"
            "       did you mean 'resort_every'?  known: dt_max, end, max_steps, resort_every\n"
            "3 errors in " + file + "; nothing was run.\n");
  EXPECT_FALSE(fs::exists(out));
  EXPECT_EQ(run_command(exe + " validate " + scenes + "/three_errors.json").exit_code, 2);
}

TEST(Cli, ValidatePlanAndDocOnAGoodScene) {
  const auto v = run_command(exe + " validate " + scenes + "/ballistic.json");
  EXPECT_EQ(v.exit_code, 0) << v.output;
  EXPECT_NE(v.output.find("valid (100 fluid particles"), std::string::npos) << v.output;
  const auto p = run_command(exe + " plan " + scenes + "/ballistic.json");
  EXPECT_EQ(p.exit_code, 0) << p.output;
  EXPECT_NE(p.output.find("1. ballistic"), std::string::npos) << p.output;
  EXPECT_NE(p.output.find("pass 1: kick-drift over fluid particles"), std::string::npos) << p.output;
  EXPECT_NE(p.output.find("talus-test-good 1.2.3"), std::string::npos) << p.output;
  // Only the start state the stage reads (velocity) is allocated, no SPH fields.
  EXPECT_NE(p.output.find("fields allocated (fluid): id, body, material, position, velocity, acceleration\n"),
            std::string::npos)
      << p.output;
  const auto d = run_command(exe + " doc ballistic");
  EXPECT_EQ(d.exit_code, 0);
  EXPECT_NE(d.output.find("dt"), std::string::npos);
  EXPECT_EQ(run_command(exe + " doc balistic").exit_code, 2);
}

// A stale plugin on TALUS_PLUGIN_PATH (another SDK ABI; edited SDK headers) is a
// warning naming it for commands that do not need it, and an error naming the
// plugin and the model only for a scene that uses one of its models.
TEST(Cli, StalePluginsOnThePathAreWarningsUntilASceneNeedsThem) {
  const std::string dir = TALUS_TEST_PLUGINS;
  const std::string stale = "TALUS_PLUGIN_PATH=" + dir + "/good:" + dir + "/wrong_abi:" + dir + "/edited_sdk " + TALUS_EXE;
  const auto p = run_command(stale + " plugins");
  EXPECT_EQ(p.exit_code, 0) << p.output;
  EXPECT_NE(p.output.find("warning: plugin 'libtalus_test_wrong_abi.so' (TALUS_PLUGIN_PATH) skipped: built for Talus "
                          "SDK ABI"),
            std::string::npos)
      << p.output;
  EXPECT_NE(p.output.find("warning: plugin 'libtalus_test_edited_sdk.so' (TALUS_PLUGIN_PATH) skipped: built with other "
                          "SDK headers or flags than this talus:"),
            std::string::npos)
      << p.output;
  EXPECT_NE(p.output.find("Scenes that use its models (rheology 'tiny_newtonian') will be refused."), std::string::npos)
      << p.output;
  EXPECT_NE(p.output.find("ballistic"), std::string::npos) << p.output;
  EXPECT_NE(p.output.find("2 libraries skipped"), std::string::npos) << p.output;

  const auto v = run_command(stale + " validate " + scenes + "/ballistic.json");
  EXPECT_EQ(v.exit_code, 0) << v.output;
  EXPECT_NE(v.output.find("valid (100 fluid particles"), std::string::npos) << v.output;
  EXPECT_NE(v.output.find("warning: plugin 'libtalus_test_edited_sdk.so'"), std::string::npos) << v.output;

  const auto needs = run_command(stale + " validate " + scenes + "/ballistic_tiny_rheology.json");
  EXPECT_EQ(needs.exit_code, 2) << needs.output;
  EXPECT_NE(needs.output.find("/materials/water/rheology/type: rheology 'tiny_newtonian' is provided by plugin "
                              "'libtalus_test_edited_sdk.so', which was refused"),
            std::string::npos)
      << needs.output;
  EXPECT_NE(needs.output.find("Rebuild it against this talus (" TALUS_VERSION_STRING ", build tree " TALUS_BINARY_DIR),
            std::string::npos)
      << needs.output;
}

// `talus doc` covers the scene file's own sections too, not only models.
TEST(Cli, DocDocumentsSceneSectionsAndShapes) {
  for (const auto& [name, key] : std::vector<std::pair<std::string, std::string>>{
           {"box_walls", "open"}, {"time", "end"}, {"bodies", "material"}, {"domain", "periodic"}, {"outputs", "every"}}) {
    const auto r = run_command(exe + " doc " + name);
    EXPECT_EQ(r.exit_code, 0) << name << "\n" << r.output;
    EXPECT_NE(r.output.find("(scene file)"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("  " + key + " "), std::string::npos) << name << " lacks " << key << "\n" << r.output;
  }
  EXPECT_EQ(run_command(exe + " doc no_such_thing").exit_code, 2);
}

// `talus example` says which of the values it printed are placeholders.
TEST(Cli, ExampleNamesItsPlaceholders) {
  const auto r = run_command(exe + " example depth_integrated_sph");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("\"release_thickness\""), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("note: placeholder values (no default; put your own): terrain"), std::string::npos)
      << r.output;
}

TEST(Cli, RestartContinuesBitForBit) {
  const std::string a = fresh_dir("restart_a"), b = fresh_dir("restart_b");
  const auto full = run_command(exe + " run " + scenes + "/ballistic.json --quiet --threads 2 --out " + a);
  ASSERT_EQ(full.exit_code, 0) << full.output;
  const std::string mid = a + "/ballistic_00000050.checkpoint";
  const std::string end = a + "/ballistic_00000100.checkpoint";
  ASSERT_TRUE(fs::exists(mid));
  ASSERT_TRUE(fs::exists(end));
  const auto resumed = run_command(exe + " run " + scenes + "/ballistic.json --quiet --threads 2 --out " + b +
                                   " --restart " + mid);
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  const std::string end_b = b + "/ballistic_00000100.checkpoint";
  ASSERT_TRUE(fs::exists(end_b));
  EXPECT_TRUE(read_file(end) == read_file(end_b)) << "restarted run differs from the uninterrupted one";
}

// The same with the wcsph stage and dynamic boundary particles: state outside the store (a wall's 1/rho scratch
// was once left at its set-up values after a restart) shows up as a difference here.
TEST(Cli, WcsphRestartWithWallsContinuesBitForBit) {
  const std::string scene = std::string(TALUS_SOURCE_DIR) + "/tests/verification/water_drop_2d.json";
  const std::string a = fresh_dir("wcsph_restart_a"), b = fresh_dir("wcsph_restart_b");
  const auto full = run_command(std::string(TALUS_EXE) + " run " + scene + " --quiet --threads 1 --out " + a);
  ASSERT_EQ(full.exit_code, 0) << full.output;
  expect_restart_ends_on_the_same_checkpoint(scene, a, b);
}

// The same scene in mixed precision: the run says which fields it keeps in float (the
// integrator's saved state), the summary lists them, and a restart still continues bit for bit.
TEST(Cli, MixedPrecisionListsItsFloatFieldsAndRestartsBitForBit) {
  auto scene_json =
      nlohmann::json::parse(read_file(std::string(TALUS_SOURCE_DIR) + "/tests/verification/water_drop_2d.json"));
  scene_json["precision"] = "mixed";
  const std::string a = fresh_dir("mixed_restart_a"), b = fresh_dir("mixed_restart_b");
  fs::create_directories(a);
  const std::string scene = a + "/water_drop_mixed.json";
  talus::test::write_file(scene, scene_json.dump(1));
  const auto full = run_command(std::string(TALUS_EXE) + " run " + scene + " --threads 1 --out " + a + " --summary " +
                                a + "/summary.json");
  ASSERT_EQ(full.exit_code, 0) << full.output;
  // Dynamic boundary particles read a fluid in float and keep their walls in float.
  const std::string fluid = "velocity, density, pressure, mass, sound_speed, acceleration, density_rate, velocity_n, "
                            "density_n";
  const std::string walls = "velocity, density, pressure, mass, sound_speed, density_rate, density_n";
  EXPECT_NE(full.output.find("talus: mixed precision: in float: fluid " + fluid + "; walls " + walls),
            std::string::npos)
      << full.output;
  const auto summary = nlohmann::json::parse(read_file(a + "/summary.json"));
  EXPECT_EQ(summary["precision"]["mode"], "mixed");
  EXPECT_EQ(summary["precision"]["fluid_in_float"], fluid);
  EXPECT_EQ(summary["precision"]["walls_in_float"], walls);
  expect_restart_ends_on_the_same_checkpoint(scene, a, b);
}

// A smoothing length far outside what SPH uses is refused at validation:
// 1e-308 dp made the kernel table read out of bounds, 1e9 dp overflowed the
// viscous support count.
TEST(Cli, SmoothingLengthOutsideItsRangeIsRefused) {
  const std::string base = read_file(std::string(TALUS_SOURCE_DIR) + "/tests/verification/water_drop_2d.json");
  for (const char* h : {"1e-308", "1e9", "0.2"}) {
    std::string text = base;
    const auto at = text.find("\"h_over_dp\": ");
    ASSERT_NE(at, std::string::npos);
    text.replace(at, text.find_first_of(",}", at) - at, std::string("\"h_over_dp\": ") + h);
    const std::string scene = fresh_dir("h_range") + "_" + h + ".json";
    talus::test::write_file(scene, text);
    const auto r = run_command(exe + " validate " + scene);
    EXPECT_EQ(r.exit_code, 2) << h << "\n" << r.output;
    EXPECT_NE(r.output.find("/kernel/h_over_dp: "), std::string::npos) << r.output;
  }
}

TEST(Cli, NonFiniteValueStopsWithParticleBodyAndPosition) {
  const std::string dir = fresh_dir("nan");
  const std::string scene = dir + "_scene.json";
  std::string text = read_file(scenes + "/ballistic.json");
  text.replace(text.find("\"dt\": 0.001"), 11, "\"dt\": 0.001, \"nan_at\": 0.02");
  talus::test::write_file(scene, text);
  const auto r = run_command(exe + " run " + scene + " --quiet --out " + dir);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("error: step 20 (t = 0.02 s): particle "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("of body 'drop' at ("), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("has non-finite velocity"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("last good output:"), std::string::npos) << r.output;
}

// The host allocated wcsph's density and pressure for run-out scenes too;
// now only the start state the pipeline's stages read.
TEST(Cli, RunoutSceneHasNoSphFields) {
  const auto p = run_command(exe + " plan " + std::string(TALUS_SOURCE_DIR) + "/share/scenes/runout_valley.json");
  EXPECT_EQ(p.exit_code, 0) << p.output;
  const auto at = p.output.find("fields allocated (fluid): ");
  ASSERT_NE(at, std::string::npos) << p.output;
  const std::string fields = p.output.substr(at, p.output.find('\n', at) - at);
  EXPECT_NE(fields.find(" velocity,"), std::string::npos) << fields;
  EXPECT_NE(fields.find(" mass,"), std::string::npos) << fields;
  EXPECT_EQ(fields.find("pressure"), std::string::npos) << fields;
  EXPECT_EQ(fields.find("density"), std::string::npos) << fields;
}

// A stage that reads a start state bodies do not give is refused at its pipeline entry.
TEST(Cli, StageReadingAnUnknownBodyFieldIsRefused) {
  const std::string scene = fresh_dir("body_field") + "_scene.json";
  std::string text = read_file(scenes + "/ballistic.json");
  text.replace(text.find("\"dt\": 0.001"), 11, "\"dt\": 0.001, \"body_field\": \"temperature\"");
  talus::test::write_file(scene, text);
  const auto r = run_command(exe + " validate " + scene);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find(scene + ": /pipeline/0: stage 'ballistic' reads the start state of the body field "
                                  "'temperature', which bodies do not give"),
            std::string::npos)
      << r.output;
}

// A particle that leaves the domain is a warning with where and when, on
// stderr as it happens (also with --quiet), and first in the summary.
TEST(Cli, ParticlesLeavingTheDomainAreWarnedAboutOncePerBody) {
  const std::string dir = fresh_dir("leave");
  const std::string scene = dir + "_scene.json";
  std::string text = read_file(scenes + "/ballistic.json");
  text.replace(text.find("\"end\": 0.1"), 10, "\"end\": 1.6");
  talus::test::write_file(scene, text);
  const auto quiet = run_command(exe + " run " + scene + " --quiet --out " + dir + " --summary " + dir + ".json");
  ASSERT_EQ(quiet.exit_code, 0) << quiet.output;
  // The drop (lowest row at y = 0.025, 1 m/s up, g = 9.81 down) reaches the floor y = -10 after 1.54 s.
  EXPECT_NE(quiet.output.find("talus: warning: step "), std::string::npos) << quiet.output;
  EXPECT_NE(quiet.output.find(" of body 'drop' left the domain at ("), std::string::npos) << quiet.output;
  EXPECT_EQ(quiet.output.find("talus: warning:"), quiet.output.rfind("talus: warning:")) << quiet.output;
  const auto summary = nlohmann::json::parse(read_file(dir + ".json"));
  ASSERT_EQ(summary["warnings"].size(), 1u) << summary.dump();
  EXPECT_GT(summary["removed"].get<int>(), 0);
  const auto loud = run_command(exe + " run " + scene + " --out " + dir + "_loud");
  const auto done = loud.output.find("talus: done:");
  ASSERT_NE(done, std::string::npos) << loud.output;
  EXPECT_NE(loud.output.find("       warning: step ", done), std::string::npos) << loud.output;
}

// The summary says where the wall time went: set-up, each stage, outputs, the host's own work.
TEST(Cli, SummaryGivesTheTimeOfEachPhase) {
  const std::string dir = fresh_dir("phases");
  const auto r = run_command(exe + " run " + scenes + "/ballistic.json --out " + dir + " --summary " + dir + ".json");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("       time: set-up "), std::string::npos) << r.output;
  const auto summary = nlohmann::json::parse(read_file(dir + ".json"));
  const auto& phases = summary["phases_s"];
  double total = phases["setup"].get<double>() + phases["outputs"].get<double>() + phases["host"].get<double>();
  ASSERT_EQ(phases["stages"].size(), summary["stages"].size()) << summary.dump();
  for (const auto& [name, seconds] : phases["stages"].items()) {
    EXPECT_TRUE(summary["stages"].contains(name)) << name;
    EXPECT_GE(seconds.get<double>(), 0.0);
    total += seconds.get<double>();
  }
  // The phases cover the run: at least its stepping wall time, less than the whole process would allow.
  EXPECT_GE(total, 0.99 * summary["wall_seconds"].get<double>()) << summary.dump();
}

// Particle-steps per second are quoted for the fluid; with the wall particles counted too (as
// bench_wcsph and DualSPHysics count them) on a line of their own, and both totals in the summary.
TEST(Cli, SummaryCountsFluidAndWallParticleSteps) {
  const std::string dir = fresh_dir("wall_steps");
  const auto r = run_command(exe + " run " + scenes + "/tank_tiny_2d.json --out " + dir + " --summary " + dir + ".json");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("M particle-steps/s counting the wall particles too"), std::string::npos) << r.output;
  const auto summary = nlohmann::json::parse(read_file(dir + ".json"));
  const auto steps = summary["steps"].get<std::uint64_t>();
  ASSERT_GT(steps, 0u);
  ASSERT_GT(summary["wall_particles"].get<std::uint64_t>(), 0u);
  EXPECT_EQ(summary["particle_steps"].get<std::uint64_t>(), steps * summary["fluid_particles"].get<std::uint64_t>());
  EXPECT_EQ(summary["wall_particle_steps"].get<std::uint64_t>(),
            steps * summary["wall_particles"].get<std::uint64_t>());
}

// The summary's peak memory is the run's own: started from a process that has
// touched 256 MiB (a shell that execs talus keeps the starter's peak in
// getrusage's ru_maxrss), a tiny run reports tens of MiB.
TEST(Cli, PeakMemoryIsTheRunsOwnNotItsStarters) {
  std::vector<char> ballast(256u << 20);
  for (std::size_t i = 0; i < ballast.size(); i += 4096) ballast[i] = static_cast<char>(i);
  const std::string dir = fresh_dir("peak_memory");
  const auto r = run_command(exe + " run " + scenes + "/ballistic.json --quiet --out " + dir + " --summary " + dir + ".json");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const double peak = nlohmann::json::parse(read_file(dir + ".json"))["peak_memory_mib"].get<double>();
  EXPECT_GT(peak, 1.0);
  EXPECT_LT(peak, 128.0) << "the starter's 256 MiB counted as the run's";
  asm volatile("" : : "r"(ballast.data()) : "memory");  // the ballast stays allocated through the run
}

TEST(Cli, UnwritableOutputFolderIsARunError) {
  const auto r = run_command(exe + " run " + scenes + "/ballistic.json --quiet --out /proc/version/out");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("error: cannot create output folder /proc/version/out"), std::string::npos) << r.output;
}

TEST(Cli, SigintWritesAResumableCheckpoint) {
  const std::string dir = fresh_dir("sigint"), scene = dir + "_scene.json";
  std::string text = read_file(scenes + "/ballistic.json");
  text.replace(text.find("\"dt\": 0.001"), 11, "\"dt\": 0.001, \"sleep\": 0.002");
  talus::test::write_file(scene, text);
  const std::string log = dir + "_log.txt";
  // Start in the background, interrupt after a while, wait for it.
  const auto r = run_command("(" + exe + " run " + scene + " --threads 1 --out " + dir + " > " + log +
                             " 2>&1 & pid=$!; sleep 0.1; kill -INT $pid; wait $pid; echo exit=$?)");
  const std::string out = read_file(log);
  EXPECT_NE(r.output.find("exit=130"), std::string::npos) << r.output << out;
  const auto pos = out.find("--restart ");
  ASSERT_NE(pos, std::string::npos) << out;
  const std::string checkpoint = out.substr(pos + 10, out.find_first_of(" \n", pos + 10) - pos - 10);
  // The printed resume command keeps the thread count (the result is bit for bit only with the same one).
  EXPECT_EQ(out.substr(pos + 10 + checkpoint.size(), 12), " --threads 1") << out;
  ASSERT_TRUE(fs::exists(checkpoint)) << checkpoint;
  const auto resumed = run_command(exe + " run " + scene + " --quiet --out " + dir + " --restart " + checkpoint);
  EXPECT_EQ(resumed.exit_code, 0) << resumed.output;
  // The interrupted-and-resumed run ends exactly where an uninterrupted one does.
  const std::string whole = fresh_dir("sigint_whole");
  ASSERT_EQ(run_command(exe + " run " + scene + " --quiet --out " + whole).exit_code, 0);
  const std::string name = "/cli_sigint_scene_00000100.checkpoint";
  ASSERT_TRUE(fs::exists(dir + name));
  EXPECT_TRUE(read_file(dir + name) == read_file(whole + name));
}

}  // namespace
