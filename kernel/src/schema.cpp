#include "schema.hpp"

#include <cmath>
#include <sstream>

#include "plugin_registry.hpp"
#include "scene_schema.hpp"
#include "talus/error.hpp"
#include "text.hpp"

namespace talus {

namespace {

using nlohmann::json;

void add_range(const ParamSpec& s, json& j) {
  if (std::isfinite(s.lower)) j[s.lower_inclusive ? "minimum" : "exclusiveMinimum"] = s.lower;
  if (std::isfinite(s.upper)) j[s.upper_inclusive ? "maximum" : "exclusiveMaximum"] = s.upper;
}

json numbers(const ParamSpec& s, int count_min, int count_max) {
  json item = {{"type", "number"}};
  add_range(s, item);
  json j = {{"type", "array"}, {"items", item}};
  if (count_min) j["minItems"] = count_min;
  if (count_max) j["maxItems"] = count_max;
  return j;
}

json spec_schema(const ParamSpec& s, PluginRegistry& registry);

json object_schema(const ParamSet& set, PluginRegistry& registry, const ParamSet* extra = nullptr,
                   const std::string& selector = {}, const std::string& selected = {}) {
  json properties = json::object();
  json required = json::array();
  if (!selector.empty()) {
    properties[selector] = {{"const", selected}};
    required.push_back(selector);
  }
  for (const ParamSet* s : {&set, extra}) {
    if (!s) continue;
    for (const auto& spec : s->specs()) {
      properties[spec.name] = spec_schema(spec, registry);
      if (spec.required) required.push_back(spec.name);
    }
  }
  json j = {{"type", "object"}, {"properties", properties}, {"additionalProperties", false}};
  if (!required.empty()) j["required"] = required;
  if (!set.summary().empty()) j["description"] = set.summary();
  return j;
}

json spec_schema(const ParamSpec& s, PluginRegistry& registry) {
  json j;
  switch (s.type) {
    case ParamType::real:
      j = {{"type", "number"}};
      add_range(s, j);
      if (s.default_real) j["default"] = *s.default_real;
      break;
    case ParamType::integer:
      j = {{"type", "integer"}};
      add_range(s, j);
      if (s.default_integer) j["default"] = *s.default_integer;
      break;
    case ParamType::boolean:
      j = {{"type", "boolean"}};
      if (s.default_boolean) j["default"] = *s.default_boolean;
      break;
    case ParamType::string:
    case ParamType::path:
      j = {{"type", "string"}};
      if (s.default_string) j["default"] = *s.default_string;
      break;
    case ParamType::choice:
      j = {{"enum", s.choices}};
      if (s.default_string) j["default"] = *s.default_string;
      break;
    case ParamType::vector:
      j = s.length ? numbers(s, s.length, s.length) : numbers(s, 2, 3);
      break;
    case ParamType::real_list: j = numbers(s, 0, 0); break;
    case ParamType::vector_list:
      j = {{"type", "array"}, {"items", s.length ? numbers(s, s.length, s.length) : numbers(s, 2, 3)}};
      break;
    case ParamType::string_list: {
      json item = s.choices.empty() ? json{{"type", "string"}} : json{{"enum", s.choices}};
      j = {{"type", "array"}, {"items", item}};
      break;
    }
    case ParamType::index_lists:
      j = {{"type", "array"},
           {"items", {{"type", "array"}, {"minItems", 3}, {"items", {{"type", "integer"}, {"minimum", 0}}}}}};
      break;
    case ParamType::json_list: j = {{"type", "array"}}; break;
    case ParamType::object: j = object_schema(*s.nested, registry); break;
    case ParamType::object_list: j = {{"type", "array"}, {"items", object_schema(*s.nested, registry)}}; break;
    case ParamType::object_map:
      j = {{"type", "object"}, {"additionalProperties", object_schema(*s.nested, registry)}};
      break;
    case ParamType::one_of: {
      json alternatives = json::array();
      for (const auto& [name, set] : s.alternatives)
        alternatives.push_back({{"type", "object"},
                                {"properties", {{name, object_schema(*set, registry)}}},
                                {"required", {name}},
                                {"additionalProperties", false}});
      j = {{"oneOf", alternatives}};
      break;
    }
    case ParamType::model:
    case ParamType::model_list: {
      json alternatives = json::array();
      for (const auto& name : registry.model_names(s.model_kind))
        if (const ParamSet* set = registry.model_params(s.model_kind, name))
          alternatives.push_back(object_schema(*set, registry, s.nested.get(), s.model_key, name));
      j = {{"oneOf", alternatives}};
      if (s.type == ParamType::model_list) j = {{"type", "array"}, {"items", j}};
      break;
    }
  }
  if (!s.doc.empty()) j["description"] = s.doc;
  if (!s.unit.empty()) j["x-unit"] = s.unit;
  return j;
}

std::string type_text(const ParamSpec& s) {
  switch (s.type) {
    case ParamType::choice: return "one of " + text::join(s.choices, "|");
    case ParamType::model: return s.model_kind + " model (\"" + s.model_key + "\")";
    case ParamType::model_list: return "list of " + s.model_kind + " models";
    case ParamType::one_of: {
      std::vector<std::string> names;
      for (const auto& [n, set] : s.alternatives) names.push_back(n);
      return "one of {" + text::join(names, "|") + "}";
    }
    case ParamType::vector: return s.length ? "vector[" + std::to_string(s.length) + "]" : "vector[dim]";
    default: return to_string(s.type);
  }
}

std::string default_text(const ParamSpec& s) {
  if (s.default_real) return text::number(*s.default_real);
  if (s.default_integer) return std::to_string(*s.default_integer);
  if (s.default_boolean) return *s.default_boolean ? "true" : "false";
  if (s.default_string) return "\"" + *s.default_string + "\"";
  if (s.default_reals) {
    std::vector<std::string> parts;
    for (double x : *s.default_reals) parts.push_back(text::number(x));
    return "[" + text::join(parts) + "]";
  }
  return s.required ? "(required)" : "(optional)";
}

json example_value(const ParamSpec& s, int dim) {
  switch (s.type) {
    case ParamType::real: {
      if (s.default_real) return *s.default_real;
      if (std::isfinite(s.lower) && std::isfinite(s.upper)) return 0.5 * (s.lower + s.upper);
      if (std::isfinite(s.lower)) return s.lower + 1.0;
      return 1.0;
    }
    case ParamType::integer:
      if (s.default_integer) return *s.default_integer;
      return std::isfinite(s.lower) ? static_cast<std::int64_t>(s.lower) + (s.lower_inclusive ? 0 : 1) : 1;
    case ParamType::boolean: return s.default_boolean.value_or(false);
    case ParamType::string: return s.default_string.value_or(s.name);
    case ParamType::path: return s.default_string.value_or(s.name + ".dat");
    case ParamType::choice: return s.default_string.value_or(s.choices.empty() ? "" : s.choices.front());
    case ParamType::vector: {
      const int n = s.length ? s.length : dim;
      std::vector<double> v = s.default_reals.value_or(std::vector<double>(n, 0.0));
      v.resize(n, 0.0);
      return v;
    }
    case ParamType::object: return example_json(*s.nested, {}, {}, dim);
    case ParamType::one_of: {
      if (s.alternatives.empty()) return json::object();
      const auto& [name, set] = s.alternatives.front();
      return json{{name, example_json(*set, {}, {}, dim)}};
    }
    default: return json::array();
  }
}

}  // namespace

json json_schema(const ParamSet& set, PluginRegistry& registry) { return object_schema(set, registry); }

json scene_json_schema(PluginRegistry& registry) {
  json j = object_schema(scene_params(), registry);
  j["$schema"] = "https://json-schema.org/draft/2020-12/schema";
  j["$id"] = "https://talus.invalid/schema/scene-1.json";
  j["title"] = "Talus scene";
  return j;
}

namespace {

// The parameter table of one set, each line indented by `indent`.
void doc_table(std::ostringstream& out, const ParamSet& set, const std::string& indent) {
  std::size_t w_name = 9, w_type = 4, w_unit = 4, w_def = 7;
  for (const auto& s : set.specs()) {
    w_name = std::max(w_name, s.name.size());
    w_type = std::max(w_type, type_text(s).size());
    w_unit = std::max(w_unit, s.unit.size());
    w_def = std::max(w_def, default_text(s).size());
  }
  auto row = [&](const std::string& a, const std::string& b, const std::string& c, const std::string& d,
                 const std::string& e, const std::string& f) {
    out << indent << a << std::string(w_name - a.size() + 2, ' ') << b << std::string(w_type - b.size() + 2, ' ') << c
        << std::string(w_unit - c.size() + 2, ' ') << d << std::string(w_def - d.size() + 2, ' ') << e
        << (f.empty() ? "" : "  [" + f + "]") << "\n";
  };
  row("parameter", "type", "unit", "default", "description", "");
  for (const auto& s : set.specs()) row(s.name, type_text(s), s.unit.empty() ? "-" : s.unit, default_text(s), s.doc, s.range_text());
  if (set.specs().empty()) out << indent << "(no parameters)\n";
}

// Each alternative of the set's one-of keys, with its own table.
void doc_alternatives(std::ostringstream& out, const ParamSet& set, const std::string& path) {
  for (const auto& s : set.specs()) {
    if (s.type != ParamType::one_of) continue;
    out << "\n  " << path << s.name << ": give exactly one of\n";
    for (const auto& [name, alt] : s.alternatives) {
      out << "\n    \"" << name << "\": " << alt->summary() << "\n";
      doc_table(out, *alt, "      ");
      doc_alternatives(out, *alt, path + s.name + "/" + name + "/");
    }
  }
}

}  // namespace

std::string doc_text(const ParamSet& set, const std::string& kind) {
  std::ostringstream out;
  out << set.name() << (kind.empty() ? "" : " (" + kind + ")") << ": " << set.summary() << "\n\n";
  doc_table(out, set, "  ");
  doc_alternatives(out, set, "");
  return out.str();
}

json example_json(const ParamSet& set, const std::string& model_key, const std::string& model_name, int dim) {
  json j = json::object();
  if (!model_key.empty()) j[model_key] = model_name;
  for (const auto& s : set.specs())
    if (s.required || s.type != ParamType::object) {
      if (s.type == ParamType::model || s.type == ParamType::model_list) continue;
      if (s.type == ParamType::one_of && !s.required) continue;
      if (!s.required && !s.default_real && !s.default_integer && !s.default_boolean && !s.default_string &&
          !s.default_reals)
        continue;
      j[s.name] = example_value(s, dim);
    }
  return j;
}

Example runnable_example(const ParamSet& set, const std::string& model_key, const std::string& model_name, int dim) {
  Example e{example_json(set, model_key, model_name, dim), {}};
  for (const auto& s : set.specs())
    if (s.required && !s.default_real && !s.default_integer && !s.default_boolean && !s.default_string &&
        !s.default_reals)
      e.placeholders.push_back(s.type == ParamType::one_of ? s.name + " (the first of its alternatives)" : s.name);
  // Optional keys the model's own checks ask for (one of two ways to give a
  // value, say) are filled in too, so the fragment validates.
  for (std::size_t round = 0; round <= set.specs().size(); ++round) {
    json body = e.json;
    if (!model_key.empty()) body.erase(model_key);
    try {
      params_from_json(set, body.dump(), dim);
      break;
    } catch (const InputError& error) {
      const std::string message = error.what();
      bool added = false;
      for (const auto& s : set.specs())
        if (!e.json.contains(s.name) && message.find("/" + s.name + ":") != std::string::npos) {
          e.json[s.name] = example_value(s, dim);
          e.placeholders.push_back(s.name);
          added = true;
        }
      if (!added) break;
    }
  }
  return e;
}

}  // namespace talus
