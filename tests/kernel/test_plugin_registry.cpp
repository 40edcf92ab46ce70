// The plugin loader: good plugin, wrong ABI, missing file, not a plugin,
// duplicate model names, lazy loading from manifests.
#include <gtest/gtest.h>

#include "plugin_registry.hpp"
#include "talus/error.hpp"
#include "talus/stage.hpp"
#include "talus/world.hpp"

namespace talus {
namespace {

const std::string plugins = TALUS_TEST_PLUGINS;

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(PluginRegistry, IndexesFromTheManifestWithoutLoading) {
  PluginRegistry r;
  r.add_location(plugins + "/good", "test");
  ASSERT_EQ(r.libraries().size(), 1u);
  EXPECT_FALSE(r.libraries()[0].loaded);
  EXPECT_FALSE(r.libraries()[0].indexed_by_loading);
  EXPECT_EQ(r.libraries()[0].plugin_name, "talus-test-good");
  EXPECT_EQ(r.libraries()[0].plugin_version, "1.2.3");
  ASSERT_NE(r.find("stage", "ballistic"), nullptr);

  // Only asking for the model's declaration loads the library.
  const ParamSet* p = r.model_params("stage", "ballistic");
  ASSERT_NE(p, nullptr);
  EXPECT_TRUE(r.libraries()[0].loaded);
  EXPECT_NE(p->find("dt"), nullptr);
  const ParamValues v = params_from_json(*p, R"({"dt": 0.5})");
  auto stage = r.create_as<Stage>("stage", "ballistic", v);
  ASSERT_NE(stage, nullptr);
  World w;
  EXPECT_DOUBLE_EQ(stage->stable_time_step(w), 0.5);
}

TEST(PluginRegistry, RefusesAnotherAbiNamingBothVersions) {
  PluginRegistry r;
  const std::string e = error_of([&] { r.add_location(plugins + "/wrong_abi", "test"); });
  const std::string expected = "error: plugin 'libtalus_test_wrong_abi.so' refused: built for Talus SDK ABI " +
                               std::to_string(sdk_abi_version + 98) + " (" + TALUS_COMPILER_ID +
                               "), this talus has ABI " + std::to_string(sdk_abi_version) + " (" + TALUS_COMPILER_ID +
                               "). Rebuild it with find_package(Talus " TALUS_VERSION_STRING ").";
  EXPECT_EQ(e.substr(0, expected.size()), expected) << e;
}

TEST(PluginRegistry, MissingFileAndNonPluginAreNamed) {
  PluginRegistry r;
  EXPECT_EQ(error_of([&] { r.add_location(plugins + "/nowhere/libx.so", "scene"); }),
            "error: plugin '" + plugins + "/nowhere/libx.so' (scene): no such file or folder");
  const std::string e = error_of([&] { r.add_location(plugins + "/not_a_plugin", "test"); });
  EXPECT_NE(e.find("is not a Talus plugin: it exports no talus_plugin_descriptor"), std::string::npos) << e;
}

TEST(PluginRegistry, DuplicateModelNamesNameBothLibraries) {
  PluginRegistry r;
  r.add_location(plugins + "/good", "test");
  const std::string e = error_of([&] { r.add_location(plugins + "/duplicate", "test"); });
  EXPECT_NE(e.find("stage model 'ballistic' is provided by two plugins"), std::string::npos) << e;
  EXPECT_NE(e.find("libtalus_test_good.so"), std::string::npos) << e;
  EXPECT_NE(e.find("libtalus_test_duplicate.so"), std::string::npos) << e;
}

TEST(PluginRegistry, LoadingALibraryTwiceIndexesItOnce) {
  PluginRegistry r;
  r.add_location(plugins + "/good", "test");
  r.add_location(plugins + "/good/libtalus_test_good.so", "scene");
  EXPECT_EQ(r.libraries().size(), 1u);
}

}  // namespace
}  // namespace talus
