// Reading a scene file: syntax (line and column), structure (every problem
// with its JSON pointer), references (material and body names), all errors
// collected and reported together. Nothing is created or written here.
#pragma once

#include "talus/config.hpp"

#include <string>
#include <vector>

#include "talus/params.hpp"

namespace talus {

class PluginRegistry;

struct Scene {
  std::string path;      // as given
  std::string name;      // file stem, used for output names
  std::string base_dir;  // relative paths in the scene resolve against it
  std::string text;      // the file's text, stored in outputs' metadata
  ParamValues values;    // validated, defaults filled
};

// Throws InputError listing every problem, ending with
// "N errors in FILE; nothing was run."
TALUS_API Scene load_scene(const std::string& path, PluginRegistry& registry);

// The same for a scene given as text (a study's variant): `path` names it in
// messages, `name` prefixes the output files, relative paths resolve against
// `base_dir`. `path_pointers`, if given, receives the JSON pointer of every
// file name in the scene (plugins, meshes, DEMs) as it is validated.
TALUS_API Scene parse_scene(std::string text, const std::string& path, const std::string& name,
                            const std::string& base_dir, PluginRegistry& registry,
                            std::vector<std::string>* path_pointers = nullptr);

// The closing line of an error report.
TALUS_API std::string error_summary(std::size_t count, const std::string& file);

}  // namespace talus
