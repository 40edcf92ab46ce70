// The plugin ABI check: what a plugin's build recorded (its descriptor, or
// the manifest written from it) against what this talus was built with. Both
// sides are the same JSON shape, so a manifest is checked without loading the
// library and a loaded descriptor is checked the same way.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "talus/plugin.hpp"

namespace talus {

// The record of this talus: SDK header hash, compiler, ABI flags, layouts.
const nlohmann::json& host_abi_record();

// The record a plugin's descriptor carries (abi_version must already match).
nlohmann::json plugin_abi_record(const PluginDescriptor& d);

// Every difference that makes the plugin unsafe to use, one phrase each
// ("SDK headers: hash 1a2b... (this talus: 3c4d...)"); empty when it is safe.
std::vector<std::string> abi_differences(const nlohmann::json& plugin, const nlohmann::json& host);

// How to rebuild a refused plugin, naming the prefix of this talus.
std::string rebuild_advice();

}  // namespace talus
