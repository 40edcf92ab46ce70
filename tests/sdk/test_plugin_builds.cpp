// Out-of-tree plugins built the way a user builds them, against an install of
// this build: with the tutorial's commands (no build type given: the plugin
// must still come out optimised), and with clang, loaded by the GCC-built
// talus.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "process.hpp"
#include "talus/build_info.hpp"

namespace fs = std::filesystem;
using talus::test::read_file;
using talus::test::run_command;

namespace {

struct Example {
  std::string prefix, source, build;
  talus::test::CommandResult built;
};

// Installs this build into a fresh prefix under tests/plugin_builds/NAME and
// builds the Carreau example against it: `cmake -S . -B build
// -DCMAKE_PREFIX_PATH=PREFIX EXTRA && cmake --build build`, as in
// docs/writing-a-rheology-plugin.md.
Example build_example(const std::string& name, const std::string& extra) {
  const std::string work = std::string(TALUS_BINARY_DIR) + "/tests/plugin_builds/" + name;
  fs::remove_all(work);
  fs::create_directories(work);
  Example e{work + "/prefix", work + "/carreau_rheology", work + "/carreau_rheology/build", {}};
  const std::string cmake = TALUS_CMAKE;
  // env -u: CMake takes a build type from the environment too.
  e.built = run_command(cmake + " --install " TALUS_BINARY_DIR " --prefix " + e.prefix + " > " + work +
                        "/install.log && cp -r " TALUS_SOURCE_DIR "/share/examples/carreau_rheology " + work +
                        " && rm -rf " + e.build + " && cd " + e.source + " && env -u CMAKE_BUILD_TYPE " + cmake +
                        " -S . -B build -DCMAKE_PREFIX_PATH=" + e.prefix + " " + extra + " && " + cmake +
                        " --build build -j2");
  return e;
}

nlohmann::json manifest_of(const Example& e) {
  return nlohmann::json::parse(read_file(e.build + "/plugins/libtalus_carreau.so.talus.json"));
}

TEST(PluginBuilds, TheTutorialsCommandsBuildAnOptimisedPlugin) {
  const Example e = build_example("tutorial", "");
  ASSERT_EQ(e.built.exit_code, 0) << e.built.output;
  EXPECT_NE(read_file(e.build + "/CMakeCache.txt").find("CMAKE_BUILD_TYPE:STRING=Release"), std::string::npos);
  const nlohmann::json m = manifest_of(e);
  EXPECT_EQ(m.at("build_type"), "Release") << m.dump(2);
  EXPECT_EQ(m.at("optimised"), true) << m.dump(2);  // __OPTIMIZE__ where the plugin compiled
  // The installed talus names its own prefix when it refuses a plugin.
  const auto stale = run_command("TALUS_PLUGIN_PATH=" TALUS_BINARY_DIR "/tests/plugins/edited_sdk " + e.prefix +
                                 "/bin/talus plugins");
  EXPECT_EQ(stale.exit_code, 0) << stale.output;
  EXPECT_NE(stale.output.find("Rebuild it against this talus (" TALUS_VERSION_STRING ", prefix " + e.prefix +
                              "): cmake -S <plugin source> -B <build> -DCMAKE_PREFIX_PATH=" + e.prefix),
            std::string::npos)
      << stale.output;
  // A build type the project chooses itself stays.
  const Example debug = build_example("tutorial_debug", "-DCMAKE_BUILD_TYPE=Debug");
  ASSERT_EQ(debug.built.exit_code, 0) << debug.built.output;
  EXPECT_EQ(manifest_of(debug).at("optimised"), false);
}

TEST(PluginBuilds, AClangBuiltPluginLoadsIntoThisTalus) {
  if (run_command("command -v clang++").exit_code != 0)
    GTEST_SKIP() << "clang++ is not installed (tools/setup.sh installs it): the clang-built plugin was not tested";
  const Example e = build_example("clang", "-DCMAKE_CXX_COMPILER=clang++ -DCMAKE_C_COMPILER=clang");
  ASSERT_EQ(e.built.exit_code, 0) << e.built.output;
  const nlohmann::json m = manifest_of(e);
  EXPECT_EQ(m.at("compiler").get<std::string>().rfind("Clang ", 0), 0u) << m.dump(2);

  // Its own unit test, built with clang too.
  const auto unit = run_command("cd " + e.build + " && ctest --output-on-failure");
  EXPECT_EQ(unit.exit_code, 0) << unit.output;
  const std::string talus = e.prefix + "/bin/talus";
  const auto listed = run_command("TALUS_PLUGIN_PATH=" + e.build + "/plugins " + talus + " plugins");
  EXPECT_EQ(listed.exit_code, 0) << listed.output;
  EXPECT_NE(listed.output.find("carreau"), std::string::npos) << listed.output;
  EXPECT_EQ(listed.output.find("warning"), std::string::npos) << listed.output;
  // The example scene loads it (from its "plugins" list) and builds the pipeline.
  const auto plan = run_command("cd " + e.source + " && " + talus + " plan scene.json");
  EXPECT_EQ(plan.exit_code, 0) << plan.output;
  EXPECT_NE(plan.output.find("example-carreau 1.0.0"), std::string::npos) << plan.output;
}

}  // namespace
