// What one strength-reduction trial found, and the per-trial CSV table.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "talus/vec3.hpp"

namespace talus::strength_reduction {

struct TrialResult {
  double factor = 0.0;        // the trial F; infinity for the gravity-loaded state
  // Failure criteria, each as measured; the stage's "failure" list says
  // which of them fail the trial (`fails`).
  bool budget = false;        // the unbalanced-force ratio did not fall below its limit within the step budget
  bool displaced = false;     // a block or monitor moved farther than the displacement limit
  bool growing = false;       // the displacement grew window after window without slowing down
  bool slip_path = false;     // at the end, free blocks were held by slipping or open joints only
  std::int64_t steps = 0;
  double ratio = 0.0;         // unbalanced-force ratio at the end
  double displacement = 0.0;  // largest block or monitor displacement from the gravity-loaded state, m
  std::uint64_t contacts = 0, open = 0, stick = 0, slip = 0, bonded = 0;
  std::uint64_t released_blocks = 0;
  double released_mass = 0.0;  // fraction of the free blocks' mass
  double dissipated = 0.0;     // work dissipated during the trial (friction, damping), J
  double wall_seconds = 0.0;
  std::vector<Vec3> monitors;  // displacement of each monitor point, m

  bool fails = false;

  bool failed() const { return fails; }
};

// "stable", or "fails: " and the criteria that fired.
std::string outcome(const TrialResult& t);
std::string csv_header(std::size_t monitors);
std::string csv_row(std::size_t trial, const TrialResult& t);

}  // namespace talus::strength_reduction
