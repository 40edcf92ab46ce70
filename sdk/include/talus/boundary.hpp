// Boundary models: how walls act on the fluid. A boundary model is its own
// interaction pass (fluid-wall), never a branch inside the fluid-fluid force
// terms. The stage that owns the fluid calls the model's passes; the concrete
// pass interfaces live beside the stage that uses them (e.g. sph_boundary.hpp).
#pragma once

#include <span>
#include <string>
#include <string_view>

#include "talus/plugin.hpp"

namespace talus {

class World;

class TALUS_API Boundary : public Model {
 public:
  ~Boundary() override;

  // Called once with every wall body that names this model: build wall
  // particles or geometry from the bodies' shapes.
  virtual void setup(World& world, std::span<const int> bodies) = 0;

  // On several MPI ranks the wall particles of world.boundary are spread over
  // the ranks with the fluid: each rank owns those in its region and holds
  // copies of the others' within a halo behind them. Empty when this model
  // works so; else why not, which the host names when it refuses the run. A
  // model that keeps nothing per wall particle outside the store need only
  // return "".
  virtual std::string why_not_on_ranks() const { return "its plugin does not say that it runs on several MPI ranks"; }
  // How far beyond one search radius of its own particles the model reads the
  // fluid (mDBC's ghost nodes lie inside the fluid), m: every rank's halo is
  // widened by the largest such reach. It must be the same on every rank.
  virtual double reach_beyond_radius() const { return 0.0; }
  // After the host moved rows of world.boundary between ranks and rebuilt the
  // halo rows behind the owned ones: row ranges and per-particle state kept
  // outside the store are stale and are rebuilt here from the store's fields.
  virtual void rows_moved(World& /*world*/) {}

  // State kept outside the stores and the block set from one step to the
  // next (a coupling's impulse still owed to its blocks), as opaque bytes for
  // checkpoints, as Stage::save_state: a restart must continue bit for bit.
  // The host writes one copy and every rank loads it, so on several ranks the
  // state must be the same on all of them (per-particle state belongs in the
  // store, which the host spreads over the ranks).
  virtual std::string save_state() const { return {}; }
  virtual void load_state(std::string_view /*bytes*/) {}
};

}  // namespace talus
