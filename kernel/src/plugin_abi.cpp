#include "plugin_abi.hpp"

#include <dlfcn.h>

#include <filesystem>
#include <sstream>

#include "talus/abi_layout.hpp"
#include "talus/build_info.hpp"
#include "talus_host_sdk_hash.hpp"  // generated at build time: TALUS_RESOLVED_SDK_HASH

namespace fs = std::filesystem;

namespace talus {

namespace {

// Differences listed before "and N more": enough to see what moved.
constexpr std::size_t max_listed = 12;

constexpr auto host_layout = abi_layout();

nlohmann::json layout_json(const AbiField* fields, std::size_t n) {
  nlohmann::json out = nlohmann::json::object();
  for (std::size_t k = 0; k < n; ++k)
    if (fields[k].name) out[fields[k].name] = fields[k].value;
  return out;
}

// "real=double;cxx11_abi=1" -> {"real": "double", "cxx11_abi": "1"}
std::vector<std::pair<std::string, std::string>> flags_of(const std::string& text) {
  std::vector<std::pair<std::string, std::string>> out;
  std::stringstream s(text);
  std::string item;
  while (std::getline(s, item, ';')) {
    const auto eq = item.find('=');
    out.emplace_back(item.substr(0, eq), eq == std::string::npos ? "" : item.substr(eq + 1));
  }
  return out;
}

std::string text_of(const nlohmann::json& record, const char* key) {
  const auto it = record.find(key);
  return it != record.end() && it->is_string() ? it->get<std::string>() : std::string();
}

}  // namespace

const nlohmann::json& host_abi_record() {
  static const nlohmann::json record = {{"sdk_hash", TALUS_RESOLVED_SDK_HASH},
                                        {"compiler", TALUS_COMPILER_ID},
                                        {"build_config", TALUS_ABI_FLAGS},
                                        {"build_type", TALUS_BUILD_TYPE},
                                        {"optimised", TALUS_ABI_OPTIMISED != 0},
                                        {"layout", layout_json(host_layout.data(), host_layout.size())}};
  return record;
}

nlohmann::json plugin_abi_record(const PluginDescriptor& d) {
  nlohmann::json r = {{"compiler", d.compiler ? d.compiler : ""}, {"build_config", d.build_config ? d.build_config : ""}};
  if (d.sdk_hash) r["sdk_hash"] = d.sdk_hash;
  if (d.build) {
    r["build_type"] = d.build->build_type ? d.build->build_type : "";
    r["optimised"] = d.build->optimised != 0;
    r["layout"] = layout_json(d.build->layout, d.build->layout ? d.build->layout_size : 0);
  }
  return r;
}

std::vector<std::string> abi_differences(const nlohmann::json& plugin, const nlohmann::json& host) {
  if (!plugin.contains("sdk_hash") || !plugin.contains("layout"))
    return {"it records no SDK header hash or layout: it was not built with talus_add_plugin()"};
  std::vector<std::string> out;
  const std::string theirs = text_of(plugin, "sdk_hash"), ours = text_of(host, "sdk_hash");
  if (theirs != ours)
    out.push_back("SDK headers: hash " + theirs + ", this talus: " + ours + " (built against edited or other headers)");

  const auto plugin_flags = flags_of(text_of(plugin, "build_config"));
  for (const auto& [key, value] : flags_of(text_of(host, "build_config"))) {
    std::string other = "(not recorded)";
    for (const auto& [k, v] : plugin_flags)
      if (k == key) other = v;
    if (other != value) out.push_back("ABI flag " + key + "=" + other + ", this talus: " + key + "=" + value);
  }

  std::vector<std::string> layout;
  const nlohmann::json& mine = host.at("layout");
  const nlohmann::json& other = plugin.at("layout");
  for (const auto& [name, value] : mine.items()) {
    if (!other.contains(name)) layout.push_back(name + " not recorded, this talus: " + value.dump());
    else if (other.at(name) != value) layout.push_back(name + " = " + other.at(name).dump() + ", this talus: " + value.dump());
  }
  for (const auto& [name, value] : other.items())
    if (!mine.contains(name)) layout.push_back(name + " = " + value.dump() + ", unknown to this talus");
  for (std::size_t k = 0; k < layout.size() && k < max_listed; ++k) out.push_back("layout: " + layout[k]);
  if (layout.size() > max_listed) out.push_back("layout: and " + std::to_string(layout.size() - max_listed) + " more");
  return out;
}

std::string rebuild_advice() {
  // Where this libtalus lives: PREFIX/lib/libtalus.so installed, BUILD/lib in a build tree.
  Dl_info info{};
  fs::path libdir;
  if (dladdr(reinterpret_cast<void*>(&rebuild_advice), &info) && info.dli_fname)
    libdir = fs::weakly_canonical(info.dli_fname).parent_path();
  const fs::path prefix = libdir.parent_path();
  std::error_code ec;
  if (!libdir.empty() && fs::exists(libdir / "cmake" / "Talus" / "TalusConfig.cmake", ec))
    return "Rebuild it against this talus (" TALUS_VERSION_STRING ", prefix " + prefix.string() +
           "): cmake -S <plugin source> -B <build> -DCMAKE_PREFIX_PATH=" + prefix.string() + " && cmake --build <build>";
  return "Rebuild it against this talus (" TALUS_VERSION_STRING ", build tree " + prefix.string() +
         ", SDK headers " TALUS_SDK_SOURCE_INCLUDE "): in-tree plugins with cmake --build " + prefix.string() +
         "; an out-of-tree plugin against an install of it (cmake --install " + prefix.string() +
         " --prefix P, then -DCMAKE_PREFIX_PATH=P)";
}

}  // namespace talus
