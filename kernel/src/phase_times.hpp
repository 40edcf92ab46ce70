// Where a run's wall time goes, for the summary: the set-up (scene read to
// the first step: filling, hydrostatic start, stage set-up, first grids),
// each stage's advance, the outputs (writers and checkpoints) and the host's
// own work between steps (time step, removals, re-sort, checks, progress).
// A short run dominated by its set-up, or a run whose host work rivals its
// pair loops, shows it here.
#pragma once

#include <chrono>
#include <vector>

namespace talus {

struct PhaseTimes {
  double setup = 0.0, outputs = 0.0, host = 0.0;  // s
  std::vector<double> stages;                      // s, per pipeline stage
};

// Seconds between successive calls of lap(), the first counted from construction.
class Stopwatch {
 public:
  Stopwatch() : last_(std::chrono::steady_clock::now()) {}
  double lap() {
    const auto now = std::chrono::steady_clock::now();
    const double seconds = std::chrono::duration<double>(now - last_).count();
    last_ = now;
    return seconds;
  }

 private:
  std::chrono::steady_clock::time_point last_;
};

}  // namespace talus
