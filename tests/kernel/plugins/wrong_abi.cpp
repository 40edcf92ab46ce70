// Test plugin: a descriptor that claims another SDK ABI, as a plugin built
// against an older Talus would. The host must refuse it before touching its
// model table.
#include "talus/plugin.hpp"

namespace {
const talus::PluginDescriptor wrong_descriptor{talus::sdk_abi_version + 98, "0000000000000000", TALUS_COMPILER_ID,
                                               TALUS_ABI_FLAGS,             "talus-test-wrong-abi", "9.9.9",
                                               nullptr,                     0,                      nullptr};
}  // namespace

BOOST_DLL_ALIAS(wrong_descriptor, talus_plugin_descriptor)
