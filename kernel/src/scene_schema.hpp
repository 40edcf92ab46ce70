// The declared structure of a scene file. Model-valued entries (eos,
// rheology, boundary, contact, stages, writers, kernel) are resolved through
// the plugin registry while validating.
#pragma once

#include "talus/config.hpp"

#include "talus/params.hpp"

namespace talus {

TALUS_API const ParamSet& scene_params();

}  // namespace talus
