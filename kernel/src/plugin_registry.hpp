// Finds, indexes and loads plugin libraries (DESIGN.md principle 5).
//
// Search order: the built-in plugin folder next to libtalus, then the folders
// in TALUS_PLUGIN_PATH, then the scene's own "plugins" list. Each library has
// a manifest (LIB.talus.json, written at build time by `talus manifest`) so
// that the index is built without executing any plugin code; only libraries
// that provide a model the scene names are loaded. A library without a
// manifest is loaded once to read its descriptor. Libraries are owned by the
// registry, loaded serially, never unloaded before the registry dies, and the
// registry must outlive every model it created.
//
// A library that fails the ABI check (plugin_abi.hpp) or cannot be loaded is
// not an error by itself: it is kept as refused, with a warning that names it
// and why, so that one stale plugin on the search path does not break
// commands that never use it. Asking for a model it provides (as far as its
// manifest or descriptor says) is the error.
#pragma once

#include "talus/config.hpp"

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <boost/dll/shared_library.hpp>
#include <nlohmann/json.hpp>

#include "talus/plugin.hpp"
#include "validator.hpp"

namespace talus {

struct ModelRecord {
  std::string kind, name, summary;
  std::size_t library = 0;  // index into PluginRegistry::libraries()
};

struct LibraryRecord {
  std::string path;
  std::string plugin_name, plugin_version;
  std::string origin;  // "built-in", "TALUS_PLUGIN_PATH", "scene"
  bool loaded = false;
  bool indexed_by_loading = false;  // no (or a stale) manifest
  std::string refused;              // why it cannot be used; empty when it can
};

class TALUS_API PluginRegistry final : public ModelCatalogue {
 public:
  PluginRegistry();
  ~PluginRegistry() override;
  PluginRegistry(const PluginRegistry&) = delete;
  PluginRegistry& operator=(const PluginRegistry&) = delete;

  // The built-in folder and TALUS_PLUGIN_PATH.
  void add_default_locations();
  // A library file or a folder of libraries (the scene's "plugins" list).
  void add_location(const std::string& path, const std::string& origin);

  // ModelCatalogue
  std::vector<std::string> model_names(std::string_view kind) const override;
  const ParamSet* model_params(std::string_view kind, std::string_view name) override;

  const ModelRecord* find(std::string_view kind, std::string_view name) const;
  // Creates a model; the caller casts it to the interface of its kind.
  std::unique_ptr<Model> create(std::string_view kind, std::string_view name, const ParamValues& values);
  template <class Interface>
  std::unique_ptr<Interface> create_as(std::string_view kind, std::string_view name, const ParamValues& values) {
    std::unique_ptr<Model> m = create(kind, name, values);
    auto* typed = dynamic_cast<Interface*>(m.get());
    if (!typed) wrong_interface(kind, name);
    m.release();
    return std::unique_ptr<Interface>(typed);
  }

  const std::vector<ModelRecord>& models() const { return models_; }
  // Models of refused libraries, as far as they are known.
  const std::vector<ModelRecord>& refused_models() const { return refused_models_; }
  // One "warning: plugin ... skipped: ..." text per refused library.
  const std::vector<std::string>& warnings() const { return warnings_; }
  const std::vector<LibraryRecord>& libraries() const { return libraries_; }

  static std::string builtin_folder();
  // Loads one library, checks its descriptor and returns its manifest JSON
  // (what `talus manifest` writes). Throws InputError on refusal.
  static nlohmann::json describe_library(const std::string& path);

 private:
  struct Loaded;
  void index_library(const std::string& path, const std::string& origin);
  const PluginDescriptor& load(std::size_t library);
  void refuse(std::size_t library, const std::string& reason, const std::vector<ModelRecord>& models);
  [[noreturn]] void refused_model(std::string_view kind, std::string_view name) const;
  const ModelEntry& entry(const ModelRecord& record);
  [[noreturn]] void wrong_interface(std::string_view kind, std::string_view name) const;

  std::vector<LibraryRecord> libraries_;
  std::vector<ModelRecord> models_;
  std::vector<ModelRecord> refused_models_;
  std::vector<std::string> warnings_;
  std::vector<std::unique_ptr<Loaded>> loaded_;  // parallel to libraries_
  std::vector<std::pair<std::string, std::unique_ptr<ParamSet>>> params_cache_;  // "kind/name"
};

}  // namespace talus
