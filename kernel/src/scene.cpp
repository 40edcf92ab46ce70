#include "scene.hpp"

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "plugin_registry.hpp"
#include "scene_schema.hpp"
#include "talus/error.hpp"
#include "text.hpp"
#include "validator.hpp"

namespace fs = std::filesystem;

namespace talus {

namespace {

// Phase 3: names that refer to other parts of the scene.
void check_references(const ParamValues& scene, Diagnostics& d) {
  std::vector<std::string> materials;
  if (scene.has("materials")) materials = scene.keys("materials");
  std::set<std::string> body_names;
  for (const auto& body : scene.objects("bodies")) {
    const std::string& name = body.string("name");
    if (!body_names.insert(name).second) d.error(body, "name", "duplicate body name '" + name + "'");
    if (body.has("material")) {
      const std::string& m = body.string("material");
      if (std::find(materials.begin(), materials.end(), m) == materials.end()) {
        const std::string guess = text::closest(m, materials);
        d.error(body, "material", "unknown material '" + m + "'",
                (guess.empty() ? "" : "did you mean '" + guess + "'?  ") + "known: " +
                    (materials.empty() ? "(no materials defined)" : text::join(materials)));
      }
    }
  }
  const auto& stages = scene.model_names("pipeline");
  if (stages.empty()) d.error(scene, "pipeline", "the pipeline is empty: name at least one stage");
  for (std::size_t i = 0; i < stages.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (stages[i] == stages[j])
        d.error(scene.file(), scene.pointer("pipeline") + "/" + std::to_string(i),
                "stage '" + stages[i] + "' appears twice in the pipeline");
}

}  // namespace

std::string error_summary(std::size_t count, const std::string& file) {
  return std::to_string(count) + (count == 1 ? " error" : " errors") + " in " + file + "; nothing was run.";
}

Scene load_scene(const std::string& path, PluginRegistry& registry) {
  std::string text;
  if (!text::read_file(path, text))
    throw InputError("error: " + path + ": cannot open scene file: " + std::strerror(errno));
  std::string base_dir = fs::path(path).parent_path().string();
  if (base_dir.empty()) base_dir = ".";
  return parse_scene(std::move(text), path, fs::path(path).stem().string(), base_dir, registry);
}

Scene parse_scene(std::string text, const std::string& path, const std::string& name, const std::string& base_dir,
                  PluginRegistry& registry, std::vector<std::string>* path_pointers) {
  Scene scene;
  scene.path = path;
  scene.text = std::move(text);
  scene.name = name;
  scene.base_dir = base_dir;

  const nlohmann::json json = parse_json(scene.text, path);  // phase 1: syntax
  Diagnostics diagnostics;

  // The scene's own plugins join the search path before models are resolved.
  if (json.is_object() && json.contains("plugins") && json["plugins"].is_array()) {
    for (std::size_t k = 0; k < json["plugins"].size(); ++k) {
      const auto& item = json["plugins"][k];
      if (!item.is_string()) continue;  // reported by the structural phase
      if (path_pointers) path_pointers->push_back("/plugins/" + std::to_string(k));
      fs::path p = item.get<std::string>();
      if (p.is_relative()) p = fs::path(scene.base_dir) / p;
      try {
        registry.add_location(p.lexically_normal().string(), "scene");
      } catch (const InputError& e) {
        std::string what = e.what();  // "error: plugin ...": the report adds its own "error: FILE: POINTER: "
        if (what.rfind("error: ", 0) == 0) what.erase(0, 7);
        diagnostics.error(path, "/plugins/" + std::to_string(k), what);
      }
    }
  }

  // Vectors are sized by the scene dimension, read first.
  int dim = 3;
  if (json.is_object() && json.contains("domain") && json["domain"].is_object()) {
    const auto& d = json["domain"];
    if (d.contains("dim") && d["dim"].is_number_integer() && (d["dim"] == 2 || d["dim"] == 3)) dim = d["dim"].get<int>();
  }

  ValidationContext context{path, scene.base_dir, dim, &registry, &diagnostics, path_pointers};
  scene.values = validate(scene_params(), json, "", context);  // phase 2: structure (+ per-set checks)
  if (diagnostics.empty()) check_references(scene.values, diagnostics);  // phase 3
  if (!diagnostics.empty())
    throw InputError(diagnostics.format() + error_summary(diagnostics.size(), path));
  return scene;
}

}  // namespace talus
