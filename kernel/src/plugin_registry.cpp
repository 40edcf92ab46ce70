#include "plugin_registry.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "library_folder.hpp"
#include "plugin_abi.hpp"
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

// A library this talus must not use: why, and the models it would provide
// (kind, name) when they could be read safely.
class PluginRefused : public InputError {
 public:
  PluginRefused(const std::string& path, std::string reason, std::vector<std::pair<std::string, std::string>> models)
      : InputError("error: plugin '" + fs::path(path).filename().string() + "' refused: " + reason + "\n       " +
                   rebuild_advice() + "\n       (" + path + ")"),
        reason_(std::move(reason)),
        models_(std::move(models)) {}
  const std::string& reason() const { return reason_; }
  const std::vector<std::pair<std::string, std::string>>& models() const { return models_; }

 private:
  std::string reason_;
  std::vector<std::pair<std::string, std::string>> models_;
};

std::string differences_text(const std::vector<std::string>& differences) {
  std::string out = "built with other SDK headers or flags than this talus:";
  for (const auto& d : differences) out += "\n         - " + d;
  return out;
}

// The model table may be read (names only, nothing called) when the types that
// describe it have this talus's layout.
bool model_table_readable(const PluginDescriptor& d) {
  if (!d.build || !d.models) return false;
  const nlohmann::json plugin = plugin_abi_record(d).at("layout");
  for (const auto& [name, value] : host_abi_record().at("layout").items())
    if ((name.find("(ModelEntry") != std::string::npos || name.find("(PluginDescriptor") != std::string::npos) &&
        (!plugin.contains(name) || plugin.at(name) != value))
      return false;
  return true;
}

// The plain fields, checked before the model table is touched.
void check_descriptor(const PluginDescriptor& d, const std::string& path) {
  if (d.abi_version != sdk_abi_version)
    throw PluginRefused(path,
                        "built for Talus SDK ABI " + std::to_string(d.abi_version) + " (" +
                            (d.compiler ? d.compiler : "?") + "), this talus has ABI " +
                            std::to_string(sdk_abi_version) + " (" TALUS_COMPILER_ID ").",
                        {});
  if (!d.models && d.model_count) throw PluginRefused(path, "its model table is null.", {});
  const std::vector<std::string> differences = abi_differences(plugin_abi_record(d), host_abi_record());
  if (differences.empty()) return;
  std::vector<std::pair<std::string, std::string>> models;
  if (model_table_readable(d))
    for (std::size_t k = 0; k < d.model_count; ++k)
      if (d.models[k].kind && d.models[k].name) models.emplace_back(d.models[k].kind, d.models[k].name);
  throw PluginRefused(path, differences_text(differences), std::move(models));
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
  const fs::path lib = library_folder();
  return lib.empty() ? std::string{} : (lib / "talus" / "plugins").string();
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
  libraries_.push_back(record);
  loaded_.emplace_back();
  try {
    if (!fresh || manifest.value("talus_manifest", 0) != manifest_version) {
      libraries_[index].indexed_by_loading = true;
      load(index);  // reads and checks the descriptor
      manifest = describe_library(path);
    } else if (manifest.value("abi", -1) != sdk_abi_version) {
      // Refuse with the descriptor's own words: load to read its plain fields.
      manifest = describe_library(path);
    } else if (const auto differences = abi_differences(manifest, host_abi_record()); !differences.empty()) {
      throw PluginRefused(path, differences_text(differences), {});
    }
  } catch (const PluginRefused& e) {
    std::vector<ModelRecord> models;
    for (const auto& [kind, name] : e.models()) models.push_back({kind, name, "", index});
    if (models.empty() && fresh && manifest.contains("models"))
      for (const auto& m : manifest.at("models")) models.push_back({m.value("kind", ""), m.value("name", ""), "", index});
    refuse(index, e.reason(), models);
    return;
  } catch (...) {
    libraries_.pop_back();
    loaded_.pop_back();
    throw;
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
    // Typically a plugin built against another libtalus (a missing symbol).
    throw PluginRefused(path, std::string("it could not be loaded: ") + e.what(), {});
  }
  if (!loaded->library.has(TALUS_DESCRIPTOR_SYMBOL))
    throw InputError("error: '" + path + "' is not a Talus plugin: it exports no " TALUS_DESCRIPTOR_SYMBOL);
  loaded->descriptor = &loaded->library.get_alias<const PluginDescriptor>(TALUS_DESCRIPTOR_SYMBOL);
  check_descriptor(*loaded->descriptor, path);
  libraries_[index].loaded = true;
  slot = std::move(loaded);
  return *slot->descriptor;
}

void PluginRegistry::refuse(std::size_t index, const std::string& reason, const std::vector<ModelRecord>& models) {
  LibraryRecord& l = libraries_[index];
  l.refused = reason;
  refused_models_.insert(refused_models_.end(), models.begin(), models.end());
  std::string provides;
  for (const auto& m : models) provides += (provides.empty() ? "" : ", ") + m.kind + " '" + m.name + "'";
  warnings_.push_back("warning: plugin '" + fs::path(l.path).filename().string() + "' (" + l.origin +
                      ") skipped: " + reason + "\n         Scenes that use its models" +
                      (provides.empty() ? "" : " (" + provides + ")") + " will be refused. " + rebuild_advice() +
                      "\n         (" + l.path + ")");
}

void PluginRegistry::refused_model(std::string_view kind, std::string_view name) const {
  for (const auto& m : refused_models_)
    if (m.kind == kind && m.name == name) {
      const LibraryRecord& l = libraries_[m.library];
      throw InputError("error: " + std::string(kind) + " '" + std::string(name) + "' is provided by plugin '" +
                       fs::path(l.path).filename().string() + "', which was refused: " + l.refused + "\n       " +
                       rebuild_advice() + "\n       (" + l.path + ")");
    }
  throw InputError("error: no " + std::string(kind) + " model named '" + std::string(name) + "'");
}

nlohmann::json PluginRegistry::describe_library(const std::string& path) {
  PluginRegistry one;
  one.libraries_.push_back({fs::weakly_canonical(path).string(), "", "", "manifest", false, true});
  one.loaded_.emplace_back();
  const PluginDescriptor& d = one.load(0);
  nlohmann::json models = nlohmann::json::array();
  for (std::size_t k = 0; k < d.model_count; ++k)
    models.push_back({{"kind", d.models[k].kind}, {"name", d.models[k].name}, {"summary", d.models[k].summary}});
  nlohmann::json out = {{"talus_manifest", manifest_version},
                        {"library", fs::path(path).filename().string()},
                        {"plugin", d.plugin_name},
                        {"version", d.plugin_version},
                        {"abi", d.abi_version},
                        {"models", models}};
  // sdk_hash, compiler, build_config, build_type, optimised, layout: checked
  // again when the manifest indexes the library.
  out.update(plugin_abi_record(d));
  return out;
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
  const PluginDescriptor* loaded = nullptr;
  try {
    loaded = &load(record.library);
  } catch (const PluginRefused& e) {
    // Indexed from a manifest that looked right, refused when loaded.
    throw InputError("error: " + record.kind + " '" + record.name + "' is provided by plugin '" +
                     fs::path(libraries_[record.library].path).filename().string() + "', which was refused: " +
                     e.reason() + "\n       " + rebuild_advice() + "\n       (" + libraries_[record.library].path +
                     ")");
  }
  const PluginDescriptor& d = *loaded;
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
  if (!record) {
    for (const auto& m : refused_models_)
      if (m.kind == kind && m.name == name) refused_model(kind, name);
    return nullptr;
  }
  auto set = std::make_unique<ParamSet>(entry(*record).describe());
  params_cache_.emplace_back(key, std::move(set));
  return params_cache_.back().second.get();
}

std::unique_ptr<Model> PluginRegistry::create(std::string_view kind, std::string_view name, const ParamValues& values) {
  const ModelRecord* record = find(kind, name);
  if (!record) refused_model(kind, name);  // names the refused plugin if one provides it
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
