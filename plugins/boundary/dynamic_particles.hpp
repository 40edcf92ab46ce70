// Dynamic boundary particles (DBC; Crespo, Gómez-Gesteira & Dalrymple 2007,
// CMC 5(3); as DualSPHysics implements them, Domínguez et al. 2022).
// Layers of wall particles carry a density from the continuity equation with
// their fluid neighbours,
//   drho_b/dt = sum_f m_f (v_b - v_f) . grad W_bf,
// never below the reference density (as DualSPHysics, so that walls never pull
// fluid in), a pressure from the EOS of the wall's reference material, and push
// on the fluid with the same symmetric pressure and viscous terms as fluid
// neighbours (the stage's fluid-wall pass over this model's wall set). Wall
// particles follow the body's prescribed "motion" if any.
// Initial wall density: the hydrostatic extrapolation of the neighbouring fluid
// pressure (Adami et al. 2012, J. Comput. Phys. 231, eq. 27) so that a column
// started hydrostatic is held from the first step.
//
// No-slip in the laminar (and Laplacian) viscous term, parameter "no_slip":
//   extrapolated (default): the wall particle enters the fluid-wall viscous
//     term with the mirrored velocity v_b* = 2 v_b - v~_b, v~_b the Shepard
//     interpolation of the fluid velocity at b, v~_b = sum_f v_f W_bf / sum_f W_bf
//     (Adami, Hu & Adams 2012, J. Comput. Phys. 231, eqs. 22-23; the idea of
//     Morris, Fox & Zhu 1997, J. Comput. Phys. 136, sec. 3.3). The velocity
//     then vanishes (relative to the wall) on the wall surface, half a spacing
//     in front of the first wall layer, not on the wall particles themselves:
//     a plane Poiseuille profile converges at second order instead of first.
//   wall_velocity: the wall particle's own (prescribed) velocity, as
//     DualSPHysics' DBC does; the no-slip plane then lies ~0.7 dp behind the
//     wall surface (first-order error in dp).
// Pressure and continuity always use the wall's own velocity, and the
// artificial viscosity (not a no-slip model) too: scenes with
// "viscosity": "artificial" are unchanged by this option.
//
// "method": "mdbc" replaces the continuity of the wall particles by the
// modified DBC (sph/ghost_nodes.hpp): every wall particle takes the pressure
// extrapolated from its ghost node, mirrored across the shape's surface
// (geometry.hpp wall_surface), as a density through the wall
// material's EOS (never below rho0), and the viscous velocity mirrored from
// the ghost node, no-slip or, with "slip": "free_slip", free-slip (which
// the artificial viscosity sees too, so that a free-slip wall never shears).
// The ghost nodes move with the wall's prescribed motion.
//
// At the end of every step a fluid particle closer than one spacing to a wall
// particle is tested against the wall's shape (geometry.hpp wall_region, in
// the wall's frame at t = 0): one inside the wall material has passed
// through it. It is put back on the nearest point of the wall surface with
// its velocity into the wall (relative to the wall) taken away, counted once
// (World::wall_crossings) and the first of each wall warned with where and
// when.
#pragma once

#include <functional>
#include <vector>

#include "talus/neighbour_grid.hpp"
#include "talus/scratch_column.hpp"
#include "talus/motion.hpp"
#include "talus/sph/boundary_pass.hpp"
#include "talus/sph/ghost_nodes.hpp"
#include "talus/sph/wall_crossings.hpp"
#include "talus/sph/wall_fields.hpp"

namespace talus::boundary {

class DynamicParticles final : public sph::SphBoundary {
 public:
  static ParamSet describe();
  enum class NoSlip { extrapolated, wall_velocity };
  enum class Method { dbc, mdbc };
  explicit DynamicParticles(const ParamValues& v);

  void setup(World& world, std::span<const int> bodies) override;
  std::string why_not_on_ranks() const override;
  double reach_beyond_radius() const override { return ghost_reach_; }
  void rows_moved(World& world) override;
  void bind(World& world, const sph::FluidSettings& settings) override;
  void begin_step(World& world) override;
  std::uint64_t fill_wall_state(World& world, const sph::FluidView& fluid) override;
  void refresh_wall_sets(World& world) override;
  std::span<const sph::WallSet> wall_sets() const override { return sets_; }
  void advance_walls(World& world, double time, double dt) override;
  void hold_fluid(World& world, double time) override;
  void describe_passes(StagePlan& plan) const override;
  // Its wall-side passes read the fluid in the type the stage keeps it in.
  bool reads_single_fluid() const override { return true; }

  std::size_t first() const { return first_; }
  std::size_t count() const { return count_; }

 private:
  void update_pressure(World& world);
  void initial_density(World& world);
  // A run of my rows in world.boundary: all of them on one rank. On several,
  // the owned rows and the halo rows: one run when they meet, two when the
  // rows of other wall models lie between.
  struct RowRange {
    std::size_t first = 0, count = 0;
    std::size_t offset = 0;  // its first particle's index among mine (ghost_, inv_rho_)
  };
  void refresh_sets(World& world);  // sets_ at the store's current arrays
  void build_cells(World& world);   // cells_ at my particles' current positions
  void lay_out(World& world);       // what depends on where my particles sit in the store
  // v_b* by store row (empty without mirror_), kept in the type of the wall velocity.
  template <class Real>
  std::span<VectorOf<Real>> viscous_velocity(World& world) const {
    if (!mirror_) return {};
    return world.boundary.column<VectorOf<Real>>(sph::wall_viscous_velocity.name);
  }
  // mDBC: each of my particles' ghost node at t = 0 (mirrored through its
  // wall's surface from its position0), then where the wall's motion has it.
  void find_ghosts(World& world);
  void place_ghosts(World& world, double time);  // ghost_ at the walls' prescribed positions
  std::uint64_t fill_continuity(World& world, const sph::FluidView& fluid);
  // My particles this rank owns: the first of mine, in ranges_[0] (on several
  // MPI ranks the rest are halo copies, whose rates are not wanted); all of
  // them on one rank.
  std::size_t owned_count(const World& world) const;
  void refresh_inverse_density(World& world);  // inv_rho_ from the store's densities
  std::uint64_t fill_from_ghost_nodes(World& world, const sph::FluidView& fluid);

  std::vector<int> bodies_;
  std::vector<std::string> body_names_;
  std::size_t first_ = 0, count_ = 0;         // my particles in world.boundary: from first_, count_ of them
  std::vector<RowRange> ranges_;              // ... in these runs of rows (one unless on several ranks)
  std::vector<std::vector<Index>> by_material_;  // wall indices per material, for the EOS calls
  std::vector<double> rho0_of_material_;
  std::vector<PrescribedMotion> motion_;       // per body slot
  std::vector<std::function<bool(const Vec3&)>> region_;  // per body slot: inside the wall material (t = 0 frame)
  std::vector<std::function<Vec3(const Vec3&)>> surface_;  // per body slot: the nearest wall surface point (t = 0)
  sph::WallCrossings crossings_;                          // fluid found inside my walls (by body slot)
  struct NearWall {
    Index fluid;        // a fluid row within reach of one of my wall particles
    std::int32_t slot;  // that wall's body slot
  };
  std::vector<std::vector<NearWall>> near_by_thread_;  // hold_fluid's finds, per OpenMP thread, in row order
  double crossing_reach_ = 0.0;                           // the largest dp of my walls
  std::vector<int> slot_of_body_;              // world body index -> slot (-1: not mine)
  bool moves_ = false;
  sph::FluidSettings settings_;
  std::vector<NeighbourGrid> cells_;  // per range
  ScratchColumn inv_rho_;  // 1/rho of my wall particles, refreshed by every fill_wall_state()
  NoSlip no_slip_ = NoSlip::extrapolated;
  Method method_ = Method::dbc;
  sph::WallSlip slip_ = sph::WallSlip::no_slip;
  // A mirrored viscous velocity: free slip, or the extrapolated no-slip with a
  // viscous term that uses it (laminar, Laplacian).
  bool mirror_ = false;
  std::vector<Vec3> ghost0_, ghost_;  // mDBC ghost nodes of my wall particles at t = 0 and now
  double ghost_reach_ = 0.0;          // mDBC: the farthest a ghost node lies from its wall particle
  std::vector<sph::WallSet> sets_;  // per range
};

}  // namespace talus::boundary
