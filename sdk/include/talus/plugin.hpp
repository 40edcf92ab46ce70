// The one descriptor a plugin library exports (DESIGN.md principle 5). The host
// reads the plain fields first (ABI version, SDK hash, compiler, build
// configuration) and refuses the library on any mismatch before it touches
// the model table.
//
//   TALUS_PLUGIN("talus-eos", "0.1.0",
//                talus::model_entry<Tait>("eos", "tait", "Tait equation of state"));
#pragma once

#include <cstddef>
#include <iterator>
#include <memory>

#include <boost/dll/alias.hpp>

#include "talus/build_info.hpp"  // generated: TALUS_SDK_HASH, TALUS_BUILD_CONFIG
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

struct PluginDescriptor {
  int abi_version;           // talus::sdk_abi_version of the SDK the plugin was built with
  const char* sdk_hash;      // hash of the SDK headers
  const char* compiler;      // e.g. "GCC 12.2"
  const char* build_config;  // real type, -march, Eigen alignment
  const char* plugin_name;
  const char* plugin_version;
  const ModelEntry* models;
  std::size_t model_count;
};

// Builds a ModelEntry for a class with `static ParamSet describe()` and a
// constructor taking `const ParamValues&`.
template <class Impl>
constexpr ModelEntry model_entry(const char* kind, const char* name, const char* summary) {
  return ModelEntry{kind, name, summary, &Impl::describe,
                    [](const ParamValues& v) -> std::unique_ptr<Model> { return std::make_unique<Impl>(v); }};
}

#define TALUS_STRINGIFY_(x) #x
#define TALUS_STRINGIFY(x) TALUS_STRINGIFY_(x)
#define TALUS_COMPILER_ID "GCC " TALUS_STRINGIFY(__GNUC__) "." TALUS_STRINGIFY(__GNUC_MINOR__)

}  // namespace talus

// The exported symbol the host looks for.
#define TALUS_DESCRIPTOR_SYMBOL "talus_plugin_descriptor"

#define TALUS_PLUGIN(PLUGIN_NAME, PLUGIN_VERSION, ...)                                            \
  namespace {                                                                                     \
  const ::talus::ModelEntry talus_plugin_models_[] = {__VA_ARGS__};                               \
  const ::talus::PluginDescriptor talus_plugin_descriptor_impl_{                                  \
      ::talus::sdk_abi_version, TALUS_SDK_HASH,     TALUS_COMPILER_ID,                           \
      TALUS_BUILD_CONFIG,       PLUGIN_NAME,        PLUGIN_VERSION,                              \
      talus_plugin_models_,     std::size(talus_plugin_models_)};                                 \
  }                                                                                               \
  BOOST_DLL_ALIAS(talus_plugin_descriptor_impl_, talus_plugin_descriptor)
