// The end of a run: the JSON summary file (`talus run --summary`, read by
// tools/verify.py) and the "talus: done" lines, from the same figures.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "phase_times.hpp"
#include "talus/config.hpp"

namespace talus {

class ParticleStore;
class Stage;
class World;
struct ScheduledWriter;

// A run on several MPI ranks: how evenly the work fell and what the halos cost.
struct RankFigures {
  int count = 1;
  double imbalance = 1.0;   // the busiest rank's fluid particle-steps over the mean
  double halo_share = 0.0;  // halo rows per owned row, over all ranks and rebuilds
  std::uint64_t rebuilds = 0;  // owners and halos rebuilt (re-sort, escape, skin)
  std::uint64_t rebalances = 0;  // new cuts after the first (cost above /ranks/rebalance_above)
  double cost_imbalance = 1.0;   // the largest measured cost of a rank over the mean the run stepped with
  double cost_imbalance_mean = 1.0;  // the same, averaged over the steps
  double peak_memory_mib_max = 0.0;  // the largest rank's
};

// What the summary reports; the references are the simulation's own.
struct RunSummary {
  const std::string& scene_path;
  const World& world;
  const std::vector<std::unique_ptr<Stage>>& stages;
  const std::vector<std::string>& stage_names;
  const std::vector<ScheduledWriter>& writers;
  const std::vector<std::string>& finish_lines;  // the stages' finish() lines
  std::uint64_t steps;                           // taken by this process (a restart counts from its checkpoint)
  std::uint64_t particle_steps;       // fluid particles, summed over the steps
  std::uint64_t wall_particle_steps;  // wall particles, the same (bench_wcsph and DualSPHysics count both)
  double wall_seconds;  // from the first step's set-up on (the scene's own set-up is in phases.setup)
  double peak_memory_mib;
  const PhaseTimes& phases;
  RankFigures ranks;
};

// The peak resident memory of this process so far, MiB.
double peak_memory_mib();

// The fields a store keeps in float (mixed precision), in registration order,
// as one text: "none" when there are none.
std::string fields_in_float(const ParticleStore& store);

// The summary file's top-level keys (what `talus study` measures may name).
TALUS_API const std::vector<std::string>& summary_keys();

// Writes `path` through a temporary file, renamed when complete; throws RunError.
void write_summary_file(const RunSummary& summary, const std::string& path);
void print_summary(const RunSummary& summary);

}  // namespace talus
