// The plugin loader: good plugin, wrong ABI, edited SDK headers, other ABI
// flags, missing file, not a plugin, duplicate model names, lazy loading from
// manifests, refused plugins as warnings.
#include <gtest/gtest.h>

#include "plugin_registry.hpp"
#include "talus/build_info.hpp"
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

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// What every refusal advises: rebuild against this talus, named by its prefix
// (the build tree here).
const std::string advice = "Rebuild it against this talus (" TALUS_VERSION_STRING ", build tree " TALUS_BINARY_DIR;

TEST(PluginRegistry, RefusesAnotherAbiNamingBothVersions) {
  PluginRegistry r;
  r.add_location(plugins + "/wrong_abi", "test");
  ASSERT_EQ(r.libraries().size(), 1u);
  const std::string reason = "built for Talus SDK ABI " + std::to_string(sdk_abi_version + 98) + " (" +
                             TALUS_COMPILER_ID + "), this talus has ABI " + std::to_string(sdk_abi_version) + " (" +
                             TALUS_COMPILER_ID + ").";
  EXPECT_EQ(r.libraries()[0].refused, reason);
  ASSERT_EQ(r.warnings().size(), 1u);
  const std::string expected = "warning: plugin 'libtalus_test_wrong_abi.so' (test) skipped: " + reason;
  EXPECT_EQ(r.warnings()[0].substr(0, expected.size()), expected) << r.warnings()[0];
  EXPECT_TRUE(contains(r.warnings()[0], advice)) << r.warnings()[0];
  // `talus manifest` on it is an error.
  const std::string e = error_of([&] { PluginRegistry::describe_library(plugins + "/wrong_abi/libtalus_test_wrong_abi.so"); });
  EXPECT_EQ(e.substr(0, 54), "error: plugin 'libtalus_test_wrong_abi.so' refused: bu") << e;
}

TEST(PluginRegistry, RefusesAPluginBuiltAgainstEditedSdkHeaders) {
  PluginRegistry r;
  r.add_location(plugins + "/edited_sdk", "test");
  ASSERT_EQ(r.libraries().size(), 1u);
  const std::string& why = r.libraries()[0].refused;
  EXPECT_TRUE(contains(why, "SDK headers: hash ")) << why;
  // The test's edit: a pointer before shear_rate.
  EXPECT_TRUE(contains(why, "layout: sizeof(ViscosityInputs) = 32, this talus: 24")) << why;
  EXPECT_TRUE(contains(why, "layout: offsetof(ViscosityInputs, shear_rate) = 8, this talus: 0")) << why;
  EXPECT_TRUE(r.models().empty());
  // Its model is known (the model table's own layout matches) but refused by name.
  ASSERT_EQ(r.refused_models().size(), 1u);
  EXPECT_EQ(r.refused_models()[0].name, "tiny_newtonian");
  const std::string e = error_of([&] { r.model_params("rheology", "tiny_newtonian"); });
  EXPECT_TRUE(contains(e, "error: rheology 'tiny_newtonian' is provided by plugin 'libtalus_test_edited_sdk.so', "
                          "which was refused: built with other SDK headers or flags than this talus:")) << e;
  EXPECT_TRUE(contains(e, advice)) << e;
  EXPECT_TRUE(contains(error_of([&] { r.create("rheology", "tiny_newtonian", {}); }), "which was refused"));
}

TEST(PluginRegistry, RefusesAPluginBuiltWithAnotherStringAbi) {
  PluginRegistry r;
  r.add_location(plugins + "/old_string_abi", "test");
  ASSERT_EQ(r.libraries().size(), 1u);
  const std::string& why = r.libraries()[0].refused;
  EXPECT_TRUE(contains(why, "ABI flag cxx11_abi=0, this talus: cxx11_abi=1")) << why;
  EXPECT_TRUE(contains(why, "layout: sizeof(String) = 8, this talus: 32")) << why;
  EXPECT_FALSE(contains(why, "SDK headers: hash")) << why;  // same headers, other flags
}

TEST(PluginRegistry, RefusesAPluginBuiltWithoutTalusAddPlugin) {
  PluginRegistry r;
  r.add_location(plugins + "/no_record", "test");
  ASSERT_EQ(r.libraries().size(), 1u);
  EXPECT_EQ(r.libraries()[0].refused,
            "built with other SDK headers or flags than this talus:\n         - it records no SDK header hash or "
            "layout: it was not built with talus_add_plugin()");
}

TEST(PluginRegistry, ARefusedPluginLeavesTheOthersUsable) {
  PluginRegistry r;
  r.add_location(plugins + "/edited_sdk", "test");
  r.add_location(plugins + "/wrong_abi", "test");
  r.add_location(plugins + "/good", "test");
  EXPECT_EQ(r.warnings().size(), 2u);
  ASSERT_NE(r.model_params("stage", "ballistic"), nullptr);
  EXPECT_TRUE(r.libraries()[2].refused.empty());
}

TEST(PluginRegistry, ManifestRecordsTheBuildAndTheLayout) {
  const nlohmann::json m = PluginRegistry::describe_library(plugins + "/good/libtalus_test_good.so");
  EXPECT_EQ(m.at("build_type"), TALUS_TEST_BUILD_TYPE);
  EXPECT_EQ(m.at("optimised"), true);
  EXPECT_EQ(m.at("compiler"), TALUS_COMPILER_ID);
  EXPECT_EQ(m.at("layout").at("sizeof(ViscosityInputs)"), 24);
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
