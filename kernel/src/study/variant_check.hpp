// Every variant of a study checked as `talus validate` checks a scene, and its
// measures against what its writers record, before any variant runs.
#pragma once

#include <string>
#include <vector>

#include "study/study_spec.hpp"
#include "study/variants.hpp"

namespace talus {
class PluginRegistry;
}

namespace talus::study {

struct CheckedVariant {
  std::string scene_text;  // runnable on its own: file names made absolute
  double bytes = 0.0;      // estimated memory of its run
};

// Throws InputError with every problem of every variant, each under the
// variant's id and values.
std::vector<CheckedVariant> check_variants(const StudySpec& spec, const std::vector<Variant>& variants,
                                           PluginRegistry& registry);

}  // namespace talus::study
