#include "study/variants.hpp"

#include <cstdio>

#include "scene.hpp"
#include "talus/error.hpp"
#include "talus/params.hpp"
#include "text.hpp"

namespace talus::study {

namespace {

// The keys of the deepest part of `pointer` that the scene has, for the hint.
std::string nearest_keys(const nlohmann::json& scene, const nlohmann::json::json_pointer& pointer) {
  nlohmann::json::json_pointer at = pointer;
  while (!at.empty()) {
    at = at.parent_pointer();
    if (scene.contains(at)) break;
  }
  const nlohmann::json& part = scene[at];
  const std::string where = at.empty() ? "the scene's top level" : at.to_string();
  if (part.is_object()) {
    std::vector<std::string> keys;
    for (const auto& [key, value] : part.items()) keys.push_back(key);
    return "keys at " + where + ": " + text::join(keys) +
           " (a key the scene leaves to its default must be written into the base scene first)";
  }
  if (part.is_array()) return where + " is an array of " + std::to_string(part.size()) + " items (indices from 0)";
  return where + " is a value, not an object";
}

}  // namespace

std::string cell_text(const nlohmann::json& value) {
  if (value.is_string()) return value.get<std::string>();
  return value.dump();
}

std::string short_text(const nlohmann::json& value) {
  std::string text = cell_text(value);
  if (text.size() <= 40) return text;
  if (value.is_array()) return "[" + std::to_string(value.size()) + " items]";
  if (value.is_object()) return "{" + std::to_string(value.size()) + " keys}";
  return text.substr(0, 37) + "...";
}

std::string Variant::label(const StudySpec& spec) const {
  std::string text;
  for (std::size_t a = 0; a < values.size() && a < spec.axes.size(); ++a)
    text += (a ? ", " : "") + spec.axes[a].name + "=" + short_text(values[a]);
  return text;
}

std::vector<Variant> expand_variants(const StudySpec& spec, const nlohmann::json& base) {
  Diagnostics d;
  std::vector<nlohmann::json::json_pointer> pointers;
  for (std::size_t a = 0; a < spec.axes.size(); ++a) {
    const std::string where = "/axes/" + std::to_string(a) + "/pointer";
    try {
      nlohmann::json::json_pointer pointer(spec.axes[a].pointer);
      if (pointer.empty())
        d.error(spec.file, where, "the empty pointer names the whole scene; name one value in it");
      else if (!base.contains(pointer))
        d.error(spec.file, where, "'" + spec.axes[a].pointer + "' names no key of the base scene " + spec.base_scene,
                nearest_keys(base, pointer));
      pointers.push_back(std::move(pointer));
    } catch (const nlohmann::json::exception& e) {
      d.error(spec.file, where, "'" + spec.axes[a].pointer + "' is not a JSON pointer (RFC 6901: \"/key/0/key\")");
      pointers.emplace_back();
    }
  }
  if (!d.empty()) throw InputError(d.format() + error_summary(d.size(), spec.file));

  std::size_t count = spec.axes.empty() ? 0 : 1;
  if (spec.zip) count = spec.axes.empty() ? 0 : spec.axes.front().values.size();
  else
    for (const auto& axis : spec.axes) count *= axis.values.size();
  const int width = std::max<int>(3, static_cast<int>(std::to_string(count).size()));

  std::vector<Variant> variants(count);
  for (std::size_t k = 0; k < count; ++k) {
    Variant& v = variants[k];
    v.index = k;
    char id[24];
    std::snprintf(id, sizeof id, "%0*zu", width, k + 1);
    v.id = id;
    v.scene = base;
    std::size_t rest = k;  // grid: mixed-radix digits, last axis fastest
    std::vector<std::size_t> pick(spec.axes.size(), k);
    if (!spec.zip)
      for (std::size_t a = spec.axes.size(); a-- > 0;) {
        pick[a] = rest % spec.axes[a].values.size();
        rest /= spec.axes[a].values.size();
      }
    for (std::size_t a = 0; a < spec.axes.size(); ++a) {
      v.values.push_back(spec.axes[a].values[pick[a]]);
      v.scene[pointers[a]] = v.values.back();
    }
  }
  return variants;
}

}  // namespace talus::study
