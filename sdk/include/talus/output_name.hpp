// File names that a scene gives for outputs (a writer's "file", a stage's
// raster prefix) must stay inside the output folder (--out): a plain name,
// no folders, no "..", nothing absolute, no control characters, and short
// enough for any file system once a suffix is added. Checked at validation,
// so `talus validate` refuses what `talus run` would write elsewhere.
#pragma once

#include <string>
#include <string_view>

#include "talus/params.hpp"

namespace talus {

// What is wrong with `name` as a file name in the output folder, or "" if nothing.
inline std::string output_name_problem(std::string_view name) {
  constexpr std::size_t longest = 200;  // leaves room for suffixes within the usual 255-byte limit
  if (name.empty()) return "an empty file name";
  if (name.size() > longest)
    return "a file name of " + std::to_string(name.size()) + " characters (at most " + std::to_string(longest) + ")";
  for (const char c : name)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) return "a control character in the file name";
  if (name.find('/') != std::string_view::npos || name.find('\\') != std::string_view::npos)
    return "a path, not a file name: outputs stay in the output folder (--out)";
  if (name == "." || name == "..") return "'" + std::string(name) + "' is not a file name";
  return {};
}

// Adds the check of member `key` (when present) to `set`.
inline void check_output_name(ParamSet& set, std::string key) {
  set.check([key](const ParamValues& v, Diagnostics& d) {
    if (!v.has(key)) return;
    const std::string problem = output_name_problem(v.string(key));
    if (!problem.empty()) d.error(v, key, problem, "give a plain file name; the output folder is set by --out");
  });
}

}  // namespace talus
