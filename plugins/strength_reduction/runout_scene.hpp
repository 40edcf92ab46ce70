// The run-out scene of the hand-off: a depth_integrated_sph scene given by the
// user (its kernel, material, basal law, time and outputs), with the release,
// terrain and strength filled in from the strength reduction and written
// beside the rasters it names.
#pragma once

#include <cstddef>
#include <string>

#include <nlohmann/json.hpp>

#include "handoff.hpp"

namespace talus::strength_reduction {

struct RunoutTemplate {
  std::string path;
  nlohmann::json scene;
  std::size_t stage = 0;  // index in /pipeline of the depth_integrated_sph stage
  std::size_t body = 0;   // index in /bodies of the released fluid body
  std::string material;
};

// Reads and checks the template: a depth_integrated_sph stage, a fluid body,
// and its material's rheology a bingham law (the law the reduced strength
// becomes). Every problem is an InputError naming the file and JSON path.
RunoutTemplate read_runout_template(const std::string& path);

// The template with: the domain on the rasters' grid, the fluid body on the
// failed mass's cells (spacing = the cell), its material's density and
// rheology (yield_stress = c / F_s, basal_friction_angle = atan(tan phi / F_s)),
// and the stage's terrain, thickness and basal-shear rasters (`prefix`_*.asc).
nlohmann::json runout_scene(const RunoutTemplate& t, const Handoff& h, const std::string& prefix, double cohesion,
                            double tan_friction, const std::string& description);

}  // namespace talus::strength_reduction
