// The one descriptor a plugin library exports (docs/DESIGN.md principle 5).
// The host reads the plain fields first (ABI version, SDK header hash, ABI
// flags, the layout record) and refuses the library on any mismatch before it
// touches the model table. The hash and the layout record come from a source
// that talus_add_plugin generates and compiles into the plugin, so they
// describe the headers and flags the plugin was really built with.
//
//   TALUS_PLUGIN("talus-eos", "0.1.0",
//                talus::model_entry<Tait>("eos", "tait", "Tait equation of state"));
#pragma once

#include <cstddef>
#include <iterator>
#include <memory>

#include <boost/dll/alias.hpp>

#include "talus/abi.hpp"
#include "talus/config.hpp"
#include "talus/params.hpp"

namespace talus {

// Every model a plugin makes derives from Model. Its virtual destructor is
// defined in libtalus, so the type information exists once for all plugins.
class TALUS_API Model {
 public:
  virtual ~Model();
};

struct ModelEntry {
  const char* kind;     // "kernel", "eos", "rheology", "boundary", "contact", "writer", "stage"
  const char* name;     // unique across all loaded libraries
  const char* summary;  // one line
  ParamSet (*describe)();
  std::unique_ptr<Model> (*create)(const ParamValues&);
};

// The first eight fields keep their places across ABI versions, so that a
// plugin built for another version is still named in the refusal.
struct PluginDescriptor {
  int abi_version;           // talus::sdk_abi_version of the SDK the plugin was built with
  const char* sdk_hash;      // hash of the SDK headers the plugin's build resolved; null without talus_add_plugin
  const char* compiler;      // e.g. "GCC 12.2", "Clang 14.0"
  const char* build_config;  // TALUS_ABI_FLAGS as the plugin was compiled
  const char* plugin_name;
  const char* plugin_version;
  const ModelEntry* models;
  std::size_t model_count;
  const PluginBuild* build;  // layout record and build type; null without talus_add_plugin
};

// Builds a ModelEntry for a class with `static ParamSet describe()` and a
// constructor taking `const ParamValues&`.
template <class Impl>
constexpr ModelEntry model_entry(const char* kind, const char* name, const char* summary) {
  return ModelEntry{kind, name, summary, &Impl::describe,
                    [](const ParamValues& v) -> std::unique_ptr<Model> { return std::make_unique<Impl>(v); }};
}

}  // namespace talus

// Defined in the source talus_add_plugin generates for each plugin. Weak: a
// library built without it links, and the host refuses it by name instead of
// failing to load it with an undefined symbol.
extern "C" {
extern const char talus_plugin_sdk_hash[] __attribute__((weak, visibility("hidden")));
extern const talus::PluginBuild talus_plugin_build __attribute__((weak, visibility("hidden")));
}

// The exported symbol the host looks for.
#define TALUS_DESCRIPTOR_SYMBOL "talus_plugin_descriptor"

#define TALUS_PLUGIN(PLUGIN_NAME, PLUGIN_VERSION, ...)                                            \
  namespace {                                                                                     \
  const ::talus::ModelEntry talus_plugin_models_[] = {__VA_ARGS__};                               \
  const ::talus::PluginDescriptor talus_plugin_descriptor_impl_{                                  \
      ::talus::sdk_abi_version, talus_plugin_sdk_hash, TALUS_COMPILER_ID,                        \
      TALUS_ABI_FLAGS,          PLUGIN_NAME,           PLUGIN_VERSION,                           \
      talus_plugin_models_,     std::size(talus_plugin_models_), &talus_plugin_build};            \
  }                                                                                               \
  BOOST_DLL_ALIAS(talus_plugin_descriptor_impl_, talus_plugin_descriptor)
