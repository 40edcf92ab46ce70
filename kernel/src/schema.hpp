// Everything generated from the declarations: the JSON Schema (2020-12,
// additionalProperties false, units as x-unit), the `talus doc` table and the
// `talus example` snippet.
#pragma once

#include "talus/config.hpp"

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "talus/params.hpp"

namespace talus {

class PluginRegistry;

// Schema of one ParamSet; model parameters become a oneOf over every model of
// their kind that the registry knows (loading those libraries).
TALUS_API nlohmann::json json_schema(const ParamSet& set, PluginRegistry& registry);
// A whole-document schema with $schema, $id and title.
TALUS_API nlohmann::json scene_json_schema(PluginRegistry& registry);

// A plain-text parameter table for `talus doc`.
TALUS_API std::string doc_text(const ParamSet& set, const std::string& kind);
// A JSON example built from defaults and ranges, for `talus example`.
TALUS_API nlohmann::json example_json(const ParamSet& set, const std::string& model_key, const std::string& model_name, int dim);

// A fragment for `talus example`: example_json plus the optional keys the
// model's checks require, and the names whose values are placeholders (no
// default to take them from).
struct Example {
  nlohmann::json json;
  std::vector<std::string> placeholders;
};
TALUS_API Example runnable_example(const ParamSet& set, const std::string& model_key, const std::string& model_name,
                                   int dim);

}  // namespace talus
