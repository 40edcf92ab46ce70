#include "field_select.hpp"

#include <algorithm>
#include <string>

#include "talus/params.hpp"

namespace talus::writers {

void declare_fields_parameter(ParamSet& p) {
  p.string_list("fields").optional().doc(
      "particle fields to write (position, and for particle files id and body, are always written); default: every "
      "field marked for output");
}

std::string field_names(const ParticleStore& store) {
  std::string out;
  for (const auto& f : store.fields()) {
    if (!out.empty()) out += ", ";
    out += f.name;
  }
  return out;
}

std::vector<FieldInfo> select_fields(const ParticleStore& store, const ParamValues& params, bool strict,
                                     bool identity) {
  std::vector<FieldInfo> out;
  auto add = [&](const FieldInfo& f) {
    if (f.name == "position") return;
    if (std::any_of(out.begin(), out.end(), [&](const FieldInfo& g) { return g.name == f.name; })) return;
    out.push_back(f);
  };
  // The validator gives an absent optional list as an empty one.
  if (!params.has("fields") || params.strings("fields").empty()) {
    for (const auto& f : store.fields())
      if (f.output) add(f);
    return out;
  }
  if (identity)
    for (const char* name : {"id", "body"})
      if (store.has(name)) add(store.info(name));
  for (const auto& name : params.strings("fields")) {
    if (store.has(name)) {
      add(store.info(name));
    } else if (strict) {
      params.fail("fields", "no particle field '" + name + "' in this scene; known: " + field_names(store));
    }
  }
  return out;
}

}  // namespace talus::writers
