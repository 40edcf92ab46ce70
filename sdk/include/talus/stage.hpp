// Solver stages: the pipeline a scene lists ("wcsph", "dda", ...). The host
// calls setup once, then every step asks each stage for its stable time step,
// takes the smallest, and advances the stages in pipeline order.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "talus/plugin.hpp"

namespace talus {

class World;

// What `talus plan` prints for a stage: its passes in order and the fields it
// reads and writes, so a user sees that an unneeded pass is absent.
struct StagePlan {
  std::vector<std::string> passes;
  std::vector<std::string> reads;
  std::vector<std::string> writes;
  std::vector<std::string> notes;
};

// The world parts a stage builds for the stages after it and those it needs
// from the stages before it, by name ("blocks": the DDA block set,
// World::blocks). The host checks the pipeline against them before any stage
// sets up, and refuses an order that cannot work with the stage to list first.
//
// `body_fields` are the fluid fields whose start state the stage reads from
// the scene's fluid bodies: "velocity" (the body's), "density" and
// "pressure" (the material's rest state, or hydrostatic), "mass"
// (rho0 dp^dim). The host allocates and fills only the ones some stage reads
// (a run-out scene has no pressure); a stage registers its other fields itself.
struct StageParts {
  std::vector<std::string> provides;
  std::vector<std::string> needs;
  std::vector<std::string> body_fields;
  // Those of body_fields the stage reads in float in a scene of mixed
  // precision: the host fills them in float where every stage allows it.
  std::vector<std::string> single_body_fields;
};

class TALUS_API Stage : public Model {
 public:
  ~Stage() override;

  // Called after construction, before setup: the bodies and materials exist.
  virtual StageParts parts(const World& /*world*/) const { return {}; }

  // Registers fields, checks the bodies and materials it handles (throwing
  // InputError with the JSON pointer on a semantic problem), allocates.
  virtual void setup(World& world) = 0;
  // On several MPI ranks each rank owns the particles in its region and holds
  // copies of the others' within a halo, which a stage's pair loops must keep
  // fresh (Parallel::refresh_halo); blocks are stepped on every rank alike.
  // Empty when this stage works so; else why not, which the host names when
  // it refuses the run.
  virtual std::string why_not_on_ranks() const { return "its plugin does not say that it runs on several MPI ranks"; }
  // Largest stable dt for the current state (infinity if no limit). A stage
  // whose bound needs its rates (accelerations) may evaluate them here, into
  // its fields, for the advance() that follows to reuse.
  virtual double stable_time_step(World& world) = 0;
  // Advances this stage's state from world.time to world.time + dt.
  virtual void advance(World& world, double dt) = 0;
  virtual StagePlan plan(const World& world) const = 0;
  // One line for the progress log (e.g. "rho dev 0.3%"), may be empty.
  virtual std::string status(const World& /*world*/) const { return {}; }

  // State that lives outside the particle store and the block set (contact
  // history, integrator counters), as opaque bytes for checkpoints. A restart
  // must continue bit for bit, so everything that influences the next step
  // and is not a store field belongs here.
  virtual std::string save_state() const { return {}; }
  virtual void load_state(std::string_view /*bytes*/) {}

  // Called once after the last step with the output folder (final rasters,
  // summaries). Lines returned are printed in the run summary.
  virtual std::vector<std::string> finish(World& /*world*/, const std::string& /*output_directory*/) { return {}; }
};

}  // namespace talus
