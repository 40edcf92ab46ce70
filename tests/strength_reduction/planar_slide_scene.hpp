// The seed's planar slide (share/scenes/planar_slide.json) with another slab
// thickness or joint, its closed-form safety factor, and a `talus run` of a
// scene in a fresh folder with the factor read back from the run summary.
#pragma once

#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace talus::test {

struct SlabJoint {
  double thickness = 8.660254037844386;  // normal to the slip plane, m
  double cohesion = 1e4;                 // Pa
  double friction = 30.0;                // deg
  double stiffness = 1e10;               // N/m per contact point
};

nlohmann::json planar_slide(const SlabJoint& joint);
// A block: a prism over y in [0, 1] of a counter-clockwise section polygon (x, z), 2038.7 kg/m^3, with a
// perfectly plastic mohr_coulomb joint (1e9 N/m, phi 20 deg, c 10 kPa).
nlohmann::json prism_block(const std::string& name, std::vector<std::pair<double, double>> section, bool fixed);
// F = tan(phi)/tan(beta) + c/(gamma t sin(beta)).
double closed_form(const SlabJoint& joint);

struct FactorRun {
  int exit_code = -1;
  std::string output, directory, scene;
  double safety_factor = std::numeric_limits<double>::quiet_NaN();
  double holds = safety_factor, fails = safety_factor;
};

// Writes `scene` to TALUS_BINARY_DIR/tests/strength_reduction/NAME.json and
// runs it with --out .../NAME (removed first) and `options`.
FactorRun run_scene(const nlohmann::json& scene, const std::string& name, const std::string& options = "");

}  // namespace talus::test
