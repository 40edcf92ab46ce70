// A study's variants: the base scene with each combination of the axes'
// values put in at the axes' JSON pointers.
#pragma once

#include "talus/config.hpp"

#include <cstddef>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "study/study_spec.hpp"

namespace talus::study {

struct Variant {
  std::size_t index = 0;
  std::string id;                      // "003": the variant's folder and row
  std::vector<nlohmann::json> values;  // one per axis, in the study's order
  nlohmann::json scene;                // the base scene with the values put in
  TALUS_API std::string label(const StudySpec& spec) const;  // "f=0.3, slope=20"
};

// Every variant, in order (grid: the last axis varies fastest). Throws
// InputError naming the study file and the axis for a pointer that names
// no key of the base scene.
TALUS_API std::vector<Variant> expand_variants(const StudySpec& spec, const nlohmann::json& base);

// The text of a JSON value as a table cell: strings bare, numbers shortest.
TALUS_API std::string cell_text(const nlohmann::json& value);
// The same, at most 40 characters: a longer array or object as "[31 items]" or
// "{4 keys}", a longer text cut (labels, the CSV table; table.json has it whole).
TALUS_API std::string short_text(const nlohmann::json& value);

}  // namespace talus::study
