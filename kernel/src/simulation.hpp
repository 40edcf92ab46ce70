// A simulation built from a validated scene: the world, the models the scene
// names (and only those), the pipeline of stages and the output schedule.
// Building it runs every setup check, so bad input is found before anything
// is written; run() then owns the time loop.
#pragma once

#include "talus/config.hpp"

#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

#include "phase_times.hpp"
#include "rank_cost.hpp"
#include "run_summary.hpp"
#include "scene.hpp"
#include "talus/world.hpp"

namespace talus {

class PluginRegistry;
namespace ranks {
class Host;
}
class Stage;
class Writer;
class Model;

struct RunOptions {
  std::string output_directory;  // default: out/SCENE_NAME
  int threads = 0;               // 0: OpenMP default
  bool quiet = false;
  bool verbose = false;
  std::string restart;           // checkpoint to continue from
  double progress_seconds = 0.0; // 0: 0.25 s on a terminal, 10 s otherwise
  std::string summary_file;      // if set: the run summary as JSON (for tools/verify.py)
};

struct ScheduledWriter {
  std::string type;
  std::unique_ptr<Writer> writer;
  double every = 0.0;              // simulated seconds, 0 if by steps
  std::uint64_t every_steps = 0;
  double next_time = 0.0;
  std::uint64_t next_step = 0;
};

class TALUS_API Simulation {
 public:
  // Builds the world and every model, runs all setup checks. Throws
  // InputError on bad input; writes nothing.
  Simulation(PluginRegistry& registry, Scene scene);
  ~Simulation();

  // Prints the resolved pipeline (`talus plan`).
  void print_plan(std::ostream& out) const;
  // Runs to the end; returns the exit code (0 done, 1 failed, 130/143 interrupted).
  int run(const RunOptions& options);

  World& world() { return world_; }
  // Every file the writers have written so far.
  std::vector<std::string> output_files() const;
  // Every time-series column the writers will record (Writer::series).
  std::vector<std::string> output_series() const;
  // Every result the writers will give at the end, as TYPE/NAME (Writer::result_names).
  std::vector<std::string> output_results() const;
  const Scene& scene() const { return scene_; }

  // Checkpoints (also used by tests): write the complete state; read it back
  // into a simulation built from the same scene.
  void write_checkpoint(const std::string& path);
  void read_checkpoint(const std::string& path);

 private:
  void build_materials();
  void build_kernel();
  void check_periodic_axes() const;
  void build_bodies();                                   // the body records
  void fill_bodies(const std::vector<FieldInfo>& fields);  // their particles, with these start fields
  void build_stages();
  std::vector<FieldInfo> check_stage_parts() const;  // the pipeline against the stages' StageParts
  void build_writers();
  void remove_escaped_particles();
  std::size_t flag_escaped_particles();  // wraps periodic axes; returns how many owned particles left the domain
  void remove_flagged_particles();
  // Several MPI ranks (simulation_ranks.cpp): share the world out, keep owners and halos current.
  // On several ranks: the host of the exchange (before a checkpoint is read,
  // which each rank reads a share of), then the first cuts.
  void start_ranks();
  void spread_over_ranks(bool restart);
  // After particles moved between ranks: cache order, halos, the wall models' rows.
  void settle_on_ranks();
  // Measures every owned particle's cost (rank_cost_); the busiest rank's over the mean.
  double cost_imbalance();
  // The busiest rank's share over the mean share of what each rank has.
  double imbalance_over_ranks(double mine) const;
  void rebuild_ranks();
  void rank_upkeep(bool resort_due);
  void refresh_halos_for_writers();  // before the writers that run on every rank
  void gather_for_writers();
  void release_after_writers();
  void wall_rows_moved();  // after the ranks moved rows: the boundary models re-lay their particles
  std::vector<Boundary*> boundary_models() const;  // each once, in the order of the first body naming it
  RankFigures figures_over_ranks(std::uint64_t own_particle_steps) const;
  void print_new_warnings();
  // On several ranks, collective: rank 0 adds every rank's new warnings to its log.
  void share_warnings();
  void resort_particles();
  void check_finite() const;
  void write_due_outputs(bool force);
  // Whether this rank runs the writer: rank 0 does; on several ranks, every
  // rank runs one that writes its owned rows into a shared file.
  bool runs_here(const ScheduledWriter& w) const;
  void close_writers();
  std::string last_output() const;

  Stopwatch since_start_;  // first member: set-up is timed from the scene on
  PhaseTimes phases_;
  PluginRegistry& registry_;
  Scene scene_;
  std::vector<std::unique_ptr<Model>> models_;  // eos, rheology, boundary, contact, kernel: destroyed first
  World world_;
  std::vector<std::unique_ptr<Stage>> stages_;
  std::vector<std::string> stage_names_;
  std::vector<ScheduledWriter> writers_;
  std::string kernel_name_;
  std::uint64_t resort_every_ = 25;
  double last_output_time_ = -1.0;
  std::string output_directory_;
  std::vector<std::uint8_t> escaped_;  // per owned particle: 1 if it left the domain; empty when none did
  std::vector<std::uint8_t> removal_warned_;  // per body: its first removal was reported
  std::size_t warnings_printed_ = 0;
  std::size_t warnings_shared_ = 0;  // this rank's log up to here went to rank 0
  std::unique_ptr<ranks::Host> ranks_;  // null on one rank
  double skin_ = 0.0;                   // how far a particle may move before the halos are rebuilt, m
  std::vector<Vec3> moved_from_;        // owned positions at the last rebuild, fluid then walls
  std::size_t fluid_over_ranks_ = 0;    // fluid particles on all ranks, counted at the last rebuild
  std::uint64_t rebuilds_ = 0, owned_rows_seen_ = 0, halo_rows_seen_ = 0;  // this rank's, at each rebuild
  double rebalance_above_ = 1.2;        // /ranks/rebalance_above
  RankCost rank_cost_;                  // each owned particle's cost, measured at the last rebuild
  std::uint64_t rebalances_ = 0;        // new cuts after the first
  double worst_cost_imbalance_ = 1.0;   // the largest the run stepped with
  double cost_imbalance_now_ = 1.0;     // the one measured at the last rebuild
  double cost_imbalance_steps_ = 0.0;   // summed over the steps, for the mean
  std::uint64_t steps_on_ranks_ = 0;
  double cut_imbalance_ = 1.0;          // what the last new cuts achieved
  bool rebalance_warned_ = false;
};

}  // namespace talus
