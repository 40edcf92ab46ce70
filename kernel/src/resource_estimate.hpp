// What a scene will need, estimated from the scene alone before anything is
// allocated: particles per body (from the shapes' volumes and surfaces and
// dp), neighbour-search cells over the domain, memory, and the number of
// steps when a fixed time step tells it. `talus plan` prints it; `talus run`
// refuses a scene that needs more memory than the machine has.
#pragma once

#include "talus/config.hpp"

#include <iosfwd>
#include <string>
#include <vector>

namespace talus {

struct Scene;
class PluginRegistry;

struct TALUS_API ResourceEstimate {
  struct Part {
    std::string pointer;  // the JSON pointer whose value sets its size: /bodies/0/dp, /domain
    std::string what;     // "fluid 'water'", "neighbour-search cells"
    double count = 0.0;   // particles or cells
    double bytes = 0.0;
  };
  std::vector<Part> parts;
  double fluid_particles = 0.0, wall_particles = 0.0, cells = 0.0;
  double steps = -1.0;        // < 0: set by the stages' stable step as the run goes
  bool steps_exact = false;   // a fixed step (else at least this many, from dt_max)
  std::string steps_from;     // its JSON pointer

  double bytes() const;
  const Part* largest() const;
};

TALUS_API ResourceEstimate estimate_resources(const Scene& scene, PluginRegistry& registry);

// Lines for `talus plan`.
TALUS_API void print_estimate(std::ostream& out, const ResourceEstimate& estimate);

// Throws InputError naming the scene file and the JSON pointer of the largest
// part if the estimate exceeds the memory available (unless --allow-large).
TALUS_API void check_resources(const Scene& scene, const ResourceEstimate& estimate);

}  // namespace talus
