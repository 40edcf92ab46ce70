// Validates JSON against declared ParamSets, collecting every problem with
// its JSON pointer (DESIGN.md "Parameters, validation, messages"): unknown
// keys with "did you mean", missing keys, wrong types, out-of-range values,
// unknown choices and model names; then each ParamSet's semantic checks.
// Defaults are filled in, so factories always see complete values.
#pragma once

#include "talus/config.hpp"

#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "talus/params.hpp"

namespace talus {

// Resolves model parameters: which models of a kind exist, and their
// declarations (loading the providing plugin on demand).
class ModelCatalogue {
 public:
  virtual ~ModelCatalogue() = default;
  virtual std::vector<std::string> model_names(std::string_view kind) const = 0;
  // Null if unknown. May throw InputError if the providing plugin is refused.
  virtual const ParamSet* model_params(std::string_view kind, std::string_view name) = 0;
};

struct ValidationContext {
  std::string file;      // shown in messages
  std::string base_dir;  // relative paths are resolved against it
  int dim = 3;           // size of vector parameters
  ModelCatalogue* models = nullptr;
  Diagnostics* diagnostics = nullptr;
  std::vector<std::string>* path_pointers = nullptr;  // if set: the pointer of every path value is added
};

TALUS_API ParamValues validate(const ParamSet& set, const nlohmann::json& json, const std::string& pointer,
                     ValidationContext& context, std::string_view owner = {});

// Parses JSON text, reporting a syntax error with line and column.
TALUS_API nlohmann::json parse_json(std::string_view text, const std::string& file);

}  // namespace talus
