// Boundary particles that move with DDA blocks (DBC floating bodies:
// Crespo et al. 2007; Domínguez et al. 2022, DualSPHysics "floating" bodies;
// rock-fluid seed §4, two-way coupling).
//
// Each block gets `layers` layers of particles on a body-frame lattice of
// spacing ~dp inside its faces (stretched per axis to a whole number of
// spacings across the block, so the first layer is half a spacing inside the
// faces of a box; the fluid's first row is fitted to dp/2 outside,
// fluid_fit.hpp), stored with body-frame offsets
// p_b; every step they are placed at x_b = X + R p_b with the block's rigid
// velocity v_b = V + w x (x_b - X). They act on the fluid like DBC walls:
// density from continuity, drho_b/dt = sum_f m_f (v_b - v_f) . grad W_bf
// (never below rho0), pressure from the fluid's EOS, and the same symmetric
// pressure and viscous terms as fluid neighbours: each block is a rigid-body
// wall set of the stage's fluid-wall pass, which sums the fluid's force on the
// block as minus the sum of the forces its particles exert on the fluid:
//   F = -sum_f m_f a_f(block),  T = sum (x_b - X) x (-m_f a_fb),
// handed back by take_reaction, once per step into external_force/torque
// (block_link.hpp).
// "method": "mdbc" gives the block particles the modified DBC instead
// (sph/ghost_nodes.hpp): each takes the pressure extrapolated from a ghost
// node mirrored across its nearest covered face, which moves with the block,
// as a density through the EOS (never below rho0), and, with laminar or
// Laplacian viscosity or "slip": "free_slip", the mirrored viscous velocity.
// At the end of every step a fluid particle inside a block (its polyhedron,
// in the block's frame) has passed through the block's particles: it is put
// back on the nearest face with its velocity into the block (relative to the
// block) taken away, counted once (World::wall_crossings), and the first per
// block warned. A block whose "faces" leave some faces without particles
// does not wall the fluid there: fluid inside it is counted and warned only.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "block_link.hpp"
#include "talus/neighbour_grid.hpp"
#include "talus/sph/boundary_pass.hpp"
#include "talus/sph/ghost_nodes.hpp"
#include "talus/sph/wall_crossings.hpp"

namespace talus::coupling {

class BlockParticles final : public sph::SphBoundary {
 public:
  static ParamSet describe();
  explicit BlockParticles(const ParamValues& v);

  void setup(World& world, std::span<const int> bodies) override;
  std::string why_not_on_ranks() const override;
  double reach_beyond_radius() const override { return ghost_reach_; }
  void rows_moved(World& world) override;
  void bind(World& world, const sph::FluidSettings& settings) override;
  void begin_step(World& world) override;
  std::uint64_t fill_wall_state(World& world, const sph::FluidView& fluid) override;
  void refresh_wall_sets(World& world) override { refresh_sets(world); }
  std::span<const sph::WallSet> wall_sets() const override { return sets_; }
  void take_reaction(World& world, std::size_t set, const Vec3& force, const Vec3& torque) override;
  void advance_walls(World& world, double time, double dt) override;
  void hold_fluid(World& world, double time) override;
  void describe_passes(StagePlan& plan) const override;
  std::string save_state() const override { return ledger_.save_state(); }
  void load_state(std::string_view bytes) override {
    ledger_.load_state(bytes, "the block_particles model's impulse ledger");
  }

  // For tests: per block of this model, in the order of the bodies.
  std::size_t blocks() const { return blocks_.size(); }
  std::size_t block_index(std::size_t k) const { return blocks_[k]; }
  std::size_t particles(std::size_t k) const { return rows_[k].size(); }
  const ImpulseLedger& ledger() const { return ledger_; }
  std::size_t removed_fluid() const { return removed_; }
  std::size_t fitted_fluid() const { return fitted_; }

 private:
  void place(World& world);
  void find_ghost_offsets(World& world);  // mDBC: from the body-frame offsets of my rows
  void place_ghosts(World& world);        // mDBC: at the blocks' current poses
  void refresh_sets(World& world);  // grids and wall sets at the current block particles
  std::span<const Vec3> positions_of(const World& world, std::size_t k);  // block k's (a view, or copied to outer_x_)
  void initial_density(World& world);
  void update_pressure(World& world);
  std::uint64_t fill_continuity(World& world, const sph::FluidView& fluid);
  std::uint64_t fill_from_ghost_nodes(World& world, const sph::FluidView& fluid);

  // Parameters.
  double dp_param_ = 0.0;  // 0: the fluid's dp
  int layers_param_ = 0;   // 0: enough to cover the kernel support
  std::string material_name_;
  std::vector<Vec3> faces_;  // outward normals of the faces that get particles (empty: all)
  std::vector<std::vector<char>> covered_;  // per block: its faces with particles (empty: all have)
  bool mdbc_ = false;
  sph::WallSlip slip_ = sph::WallSlip::no_slip;

  std::vector<int> bodies_;
  std::vector<std::string> names_;
  std::vector<std::size_t> blocks_;       // index in world.blocks per body
  // Per block, its particles' rows in world.boundary, ascending: one range of
  // rows on one rank; on several, its owned rows first, then its halo copies.
  std::vector<std::vector<Index>> rows_;
  std::vector<Index> all_;                // my particles in world.boundary (EOS batch)
  std::vector<Vec3> outer_x_;             // one block's positions, for a pass over its particles
  int material_ = -1;
  double rho0_ = 0.0, dp_ = 0.0;
  int layers_ = 0;
  std::size_t removed_ = 0;
  std::size_t fitted_ = 0;  // fluid particles moved onto the faces at the start (fluid_fit.hpp)
  sph::FluidSettings settings_;
  std::vector<NeighbourGrid> cells_;  // per block
  std::vector<sph::WallSet> sets_;         // per block
  std::vector<double> inv_rho_;            // 1/rho of my particles, refreshed by every fill_wall_state()
  // mDBC, indexed like world.boundary (only my rows are used): body-frame
  // ghost offsets and ghost nodes now; the farthest ghost node from its particle.
  std::vector<Vec3> ghost_offset_, ghost_;
  double ghost_reach_ = 0.0;
  // One block's owned particles, gathered for the extrapolation, and its results.
  struct OwnedNodes {
    std::vector<Index> rows;
    std::vector<Vec3> wall, ghost, velocity, viscous;
    std::vector<double> pressure;
    void clear() { rows.clear(), wall.clear(), ghost.clear(), velocity.clear(); }
    void add(Index row, const Vec3& x, const Vec3& g, const Vec3& v) {
      rows.push_back(row), wall.push_back(x), ghost.push_back(g), velocity.push_back(v);
    }
    void size_outputs(bool mirror) {
      pressure.resize(rows.size());
      viscous.resize(mirror ? rows.size() : 0);
    }
  };
  OwnedNodes nodes_;
  bool mirror_ = false;  // a mirrored viscous velocity (mdbc with laminar/Laplacian viscosity, or free slip)
  std::vector<std::uint8_t> inside_;          // per fluid particle: inside the block being checked
  std::vector<Vec3> impulse_, angular_;       // per block: what this rank's fluid put back gave it this step
  sph::WallCrossings crossings_;              // fluid found inside my blocks (by block)
  ImpulseLedger ledger_;
};

}  // namespace talus::coupling
