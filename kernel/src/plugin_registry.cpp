#include "plugin_registry.hpp"

#include <dlfcn.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "talus/build_info.hpp"
#include "talus/error.hpp"
#include "text.hpp"

namespace fs = std::filesystem;

namespace talus {

namespace {

constexpr int manifest_version = 1;

// "libx.so" or a versioned "libx.so.1.2", not the manifest "libx.so.talus.json".
bool is_library(const fs::path& p) {
  const std::string name = p.filename().string();
  const auto so = name.rfind(".so");
  if (so == std::string::npos) return false;
  for (std::size_t k = so + 3; k < name.size(); ++k)
    if (!std::isdigit(static_cast<unsigned char>(name[k])) && name[k] != '.') return false;
  return true;
}

std::string manifest_path(const std::string& library) { return library + ".talus.json"; }

// The plain fields, checked before the model table is touched.
void check_descriptor(const PluginDescriptor& d, const std::string& path) {
  const std::string file = fs::path(path).filename().string();
  const std::string ours = std::string("ABI ") + std::to_string(sdk_abi_version) + " (" + TALUS_COMPILER_ID + ")";
  const std::string rebuild = " Rebuild it with find_package(Talus " TALUS_VERSION_STRING ").";
  if (d.abi_version != sdk_abi_version)
    throw InputError("error: plugin '" + file + "' refused: built for Talus SDK ABI " + std::to_string(d.abi_version) +
                     " (" + (d.compiler ? d.compiler : "?") + "), this talus has " + ours + "." + rebuild + "\n       (" +
                     path + ")");
  auto differs = [&](const char* what, const char* theirs, const char* mine) {
    if (!theirs || std::string(theirs) != mine)
      throw InputError("error: plugin '" + file + "' refused: built with " + what + " '" + (theirs ? theirs : "?") +
                       "', this talus has '" + mine + "'." + rebuild + "\n       (" + path + ")");
  };
  differs("SDK headers", d.sdk_hash, TALUS_SDK_HASH);
  differs("compiler", d.compiler, TALUS_COMPILER_ID);
  differs("build configuration", d.build_config, TALUS_BUILD_CONFIG);
  if (!d.models && d.model_count) throw InputError("error: plugin '" + file + "' refused: its model table is null");
}

}  // namespace

struct PluginRegistry::Loaded {
  boost::dll::shared_library library;
  const PluginDescriptor* descriptor = nullptr;
};

PluginRegistry::PluginRegistry() = default;

// Models must already be gone; libraries are released last, in reverse order.
PluginRegistry::~PluginRegistry() {
  params_cache_.clear();
  while (!loaded_.empty()) loaded_.pop_back();
}

std::string PluginRegistry::builtin_folder() {
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&PluginRegistry::builtin_folder), &info) && info.dli_fname) {
    const fs::path lib = fs::weakly_canonical(info.dli_fname);
    return (lib.parent_path() / "talus" / "plugins").string();
  }
  return {};
}

void PluginRegistry::add_default_locations() {
  const std::string builtin = builtin_folder();
  if (!builtin.empty() && fs::is_directory(builtin)) add_location(builtin, "built-in");
  if (const char* env = std::getenv("TALUS_PLUGIN_PATH")) {
    std::stringstream s(env);
    std::string item;
    while (std::getline(s, item, ':'))
      if (!item.empty()) {
        if (!fs::exists(item))
          throw InputError("error: TALUS_PLUGIN_PATH: '" + item + "' does not exist");
        add_location(item, "TALUS_PLUGIN_PATH");
      }
  }
}

void PluginRegistry::add_location(const std::string& path, const std::string& origin) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) {
    std::vector<fs::path> files;
    for (const auto& e : fs::directory_iterator(path))
      if (e.is_regular_file() && is_library(e.path())) files.push_back(e.path());
    std::sort(files.begin(), files.end());
    for (const auto& f : files) index_library(f.string(), origin);
  } else if (fs::is_regular_file(path, ec)) {
    index_library(path, origin);
  } else {
    throw InputError("error: plugin '" + path + "' (" + origin + "): no such file or folder");
  }
}

void PluginRegistry::index_library(const std::string& raw_path, const std::string& origin) {
  const std::string path = fs::weakly_canonical(raw_path).string();
  for (const auto& l : libraries_)
    if (l.path == path) return;  // listed twice (e.g. built-in and scene): once is enough

  LibraryRecord record;
  record.path = path;
  record.origin = origin;
  nlohmann::json manifest;
  const std::string mpath = manifest_path(path);
  std::error_code ec;
  const bool fresh = fs::exists(mpath, ec) && fs::last_write_time(mpath, ec) >= fs::last_write_time(path, ec);
  if (fresh) {
    std::ifstream in(mpath);
    try {
      manifest = nlohmann::json::parse(in);
    } catch (const std::exception& e) {
      throw InputError("error: plugin manifest '" + mpath + "' is not valid JSON: " + e.what());
    }
  }
  const std::size_t index = libraries_.size();
  if (!fresh || manifest.value("talus_manifest", 0) != manifest_version) {
    record.indexed_by_loading = true;
    libraries_.push_back(record);
    loaded_.emplace_back();
    try {
      load(index);  // reads and checks the descriptor; throws on refusal
    } catch (...) {
      libraries_.pop_back();
      loaded_.pop_back();
      throw;
    }
    manifest = describe_library(path);
  } else {
    if (manifest.value("abi", -1) != sdk_abi_version) {
      // Refuse with the descriptor's own words: load to read its plain fields.
      describe_library(path);
    }
    libraries_.push_back(record);
    loaded_.emplace_back();
  }
  libraries_[index].plugin_name = manifest.value("plugin", "");
  libraries_[index].plugin_version = manifest.value("version", "");
  for (const auto& m : manifest.at("models")) {
    ModelRecord r{m.at("kind"), m.at("name"), m.value("summary", ""), index};
    if (const ModelRecord* other = find(r.kind, r.name))
      throw InputError("error: " + r.kind + " model '" + r.name + "' is provided by two plugins: '" +
                       libraries_[other->library].path + "' and '" + path + "'\n       remove one of them from the "
                       "plugin search path");
    models_.push_back(std::move(r));
  }
}

const PluginDescriptor& PluginRegistry::load(std::size_t index) {
  auto& slot = loaded_[index];
  if (slot) return *slot->descriptor;
  const std::string& path = libraries_[index].path;
  auto loaded = std::make_unique<Loaded>();
  try {
    loaded->library.load(path, boost::dll::load_mode::rtld_now | boost::dll::load_mode::rtld_local);
  } catch (const std::exception& e) {
    throw InputError("error: plugin '" + path + "' could not be loaded: " + e.what());
  }
  if (!loaded->library.has(TALUS_DESCRIPTOR_SYMBOL))
    throw InputError("error: '" + path + "' is not a Talus plugin: it exports no " TALUS_DESCRIPTOR_SYMBOL);
  loaded->descriptor = &loaded->library.get_alias<const PluginDescriptor>(TALUS_DESCRIPTOR_SYMBOL);
  check_descriptor(*loaded->descriptor, path);
  libraries_[index].loaded = true;
  slot = std::move(loaded);
  return *slot->descriptor;
}

nlohmann::json PluginRegistry::describe_library(const std::string& path) {
  PluginRegistry one;
  one.libraries_.push_back({fs::weakly_canonical(path).string(), "", "", "manifest", false, true});
  one.loaded_.emplace_back();
  const PluginDescriptor& d = one.load(0);
  nlohmann::json models = nlohmann::json::array();
  for (std::size_t k = 0; k < d.model_count; ++k)
    models.push_back({{"kind", d.models[k].kind}, {"name", d.models[k].name}, {"summary", d.models[k].summary}});
  return {{"talus_manifest", manifest_version},
          {"library", fs::path(path).filename().string()},
          {"plugin", d.plugin_name},
          {"version", d.plugin_version},
          {"abi", d.abi_version},
          {"sdk_hash", d.sdk_hash},
          {"compiler", d.compiler},
          {"build_config", d.build_config},
          {"models", models}};
}

std::vector<std::string> PluginRegistry::model_names(std::string_view kind) const {
  std::vector<std::string> out;
  for (const auto& m : models_)
    if (m.kind == kind) out.push_back(m.name);
  std::sort(out.begin(), out.end());
  return out;
}

const ModelRecord* PluginRegistry::find(std::string_view kind, std::string_view name) const {
  for (const auto& m : models_)
    if (m.kind == kind && m.name == name) return &m;
  return nullptr;
}

const ModelEntry& PluginRegistry::entry(const ModelRecord& record) {
  const PluginDescriptor& d = load(record.library);
  for (std::size_t k = 0; k < d.model_count; ++k)
    if (record.kind == d.models[k].kind && record.name == d.models[k].name) return d.models[k];
  throw InputError("error: plugin '" + libraries_[record.library].path + "' no longer provides " + record.kind + " '" +
                   record.name + "' (its manifest is stale: rebuild it or run `talus manifest` on it)");
}

const ParamSet* PluginRegistry::model_params(std::string_view kind, std::string_view name) {
  const std::string key = std::string(kind) + "/" + std::string(name);
  for (const auto& [k, set] : params_cache_)
    if (k == key) return set.get();
  const ModelRecord* record = find(kind, name);
  if (!record) return nullptr;
  auto set = std::make_unique<ParamSet>(entry(*record).describe());
  params_cache_.emplace_back(key, std::move(set));
  return params_cache_.back().second.get();
}

std::unique_ptr<Model> PluginRegistry::create(std::string_view kind, std::string_view name, const ParamValues& values) {
  const ModelRecord* record = find(kind, name);
  if (!record) throw InputError("error: no " + std::string(kind) + " model named '" + std::string(name) + "'");
  auto model = entry(*record).create(values);
  if (!model) throw InputError("error: the factory of " + std::string(kind) + " '" + std::string(name) + "' returned nothing");
  return model;
}

void PluginRegistry::wrong_interface(std::string_view kind, std::string_view name) const {
  const ModelRecord* r = find(kind, name);
  throw InputError("error: plugin '" + (r ? libraries_[r->library].path : std::string("?")) + "' declares '" +
                   std::string(name) + "' as a " + std::string(kind) + " model, but the object it makes does not "
                   "implement the " + std::string(kind) + " interface");
}

}  // namespace talus
