// Test plugin: a descriptor that claims another SDK ABI, as a plugin built
// against an older Talus would. The host must refuse it before touching its
// model table.
#include "talus/plugin.hpp"

namespace {
const talus::PluginDescriptor wrong_descriptor{talus::sdk_abi_version + 98, TALUS_SDK_HASH, TALUS_COMPILER_ID,
                                               TALUS_BUILD_CONFIG,          "talus-test-wrong-abi", "9.9.9",
                                               nullptr,                     0};
}  // namespace

BOOST_DLL_ALIAS(wrong_descriptor, talus_plugin_descriptor)
