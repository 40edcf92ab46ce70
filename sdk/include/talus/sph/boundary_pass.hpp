// Wall models of the wcsph stage (DESIGN.md: "Boundaries are separate
// interaction passes with their own neighbour lists and batch hooks that fill
// wall state; force terms never branch on the boundary type").
//
// A wall model supplies data; the stage runs the passes. A model gives its
// wall sets (positions, the fields the pair terms read, its neighbour grid),
// fills their state from the fluid in a batch hook (DBC continuity, the
// extrapolated no-slip velocity), moves its walls, and takes back the
// reaction of the fluid on a rigid body. The stage runs the fluid-fluid and
// the fluid-wall passes with one set of pair terms, so every wall model sees
// the fluid's mu_eff the same way. Penalty walls, which have no wall
// particles, add their forces directly (add_direct_forces).
//
// Call order in one stage substep (every integrator):
//   begin_step(world)                   once per step, state at t^n
//   fill_wall_state(world, fluid)       wall-side passes at the current state; the
//                                       wall sets are valid after it
//   (the stage's fluid-wall passes over wall_sets(); take_reaction per body set)
//   add_direct_forces(world, fluid, rates)
//   advance_walls(world, t, dt)         wall state at time t = t^n + dt from the
//                                       state saved by begin_step and the last rates
// and, once the step has moved the fluid to t^{n+1}:
//   hold_fluid(world, t^{n+1})          fluid found inside a wall put back on its surface
// With summation density the stage adds sum_b m_b W_ib over every wall set to
// rho_i before the force pass, after refresh_wall_sets (the first evaluation
// after bind or a restart comes before any fill_wall_state).
#pragma once

#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "talus/boundary.hpp"
#include "talus/kernel_table.hpp"
#include "talus/sph/fluid_terms.hpp"
#include "talus/neighbour_grid.hpp"
#include "talus/stage.hpp"
#include "talus/vec3.hpp"

namespace talus {
class World;
}

namespace talus::sph {

// What the stage tells its wall models once, at its setup (after every
// model's Boundary::setup has run and the fluid exists).
struct FluidSettings {
  const KernelTable* kernel = nullptr;
  bool summation_density = false;
  Vec3 lo, hi;  // bounds the fluid's neighbour grid covers
  // True with laminar and Laplacian viscosity, whose no-slip a model may
  // impose with a mirrored WallSet::viscous_velocity; when false (artificial
  // viscosity) a model gives its walls' own velocity, or a free-slip one.
  bool viscous_velocity = false;
  // The fluid's neighbour grid, built on the fluid as bind() receives it (for
  // the walls' initial state; the stage rebuilds it every step, so not kept).
  // A model whose bind() removes or moves fluid particles builds its own.
  const NeighbourGrid* cells = nullptr;
};

// Read-only view of the fluid for one pass; `cells` is the fluid's
// neighbour grid, built on `position`.
struct FluidView {
  const NeighbourGrid* cells = nullptr;
  std::span<const Vec3> position, velocity;
  std::span<const double> density, pressure, sound_speed, mass;
  std::span<const std::int32_t> material;
  // Apparent viscosity mu_eff per fluid particle (Pa s) when the stage runs the
  // three-pass non-Newtonian / turbulent viscosity; empty otherwise.
  std::span<const double> viscosity;
  std::span<const double> inv_density;  // 1/rho per fluid particle
  // In a scene of mixed precision whose wall models all read a fluid in float
  // (SphBoundary::reads_single_fluid), the stage keeps velocity, density,
  // pressure, sound speed, mass and 1/rho in float: then `single` points at
  // them (and at the materials) and the spans of those six are empty.
  NeighboursF single;

  bool in_single() const { return single.density != nullptr; }
  // The fluid as the neighbour set of a wall-side pass, in double.
  Neighbours neighbours() const {
    return {velocity.data(), density.data(),     pressure.data(), sound_speed.data(), mass.data(),
            material.data(), inv_density.data(), viscosity.data()};
  }
  // f(fields) with the fluid's NeighbourFields in the type they are kept in.
  template <class F>
  decltype(auto) visit_neighbours(F&& f) const {
    return in_single() ? f(single) : f(neighbours());
  }
};

// The fluid's rates; a wall adds to them (never overwrites).
struct FluidRates {
  std::span<Vec3> acceleration;     // m/s^2
  std::span<double> density_rate;   // kg/m^3/s (continuity; unused with summation density)
  // The largest |v_ij.x_ij|/(r^2+eta^2) of any pair, 1/s, for the time-step
  // bound: one value for the whole fluid, raised, never lowered (a pass on
  // several threads takes its own maximum first).
  double* visc_max = nullptr;
  // Where the fluid is in float (FluidView::in_single) its rates are too:
  // then these hold them and the two spans above are empty.
  std::span<Vec3f> acceleration_single;
  std::span<float> density_rate_single;
};

// A rigid body a wall set belongs to: the fluid's reaction on it is summed
// (force, and torque about `centre`) and handed back by take_reaction.
struct RigidBodyFrame {
  Vec3 centre;  // the body's centroid
  Vec3 lo, hi;  // a box holding the body (its wall particles inside); fluid farther than the kernel support is skipped
};

// One set of wall particles as the fluid's pair terms see it.
struct WallSet {
  const NeighbourGrid* cells = nullptr;  // built on `position`
  std::span<const Vec3> position;
  // The wall particles' fields: velocity (their own, seen by pressure, continuity
  // and artificial viscosity), density, pressure, sound_speed, mass, material,
  // inv_density (1/rho, refreshed with the density).
  Neighbours fields;
  // The velocity the viscous terms see (a mirrored no-slip or free-slip
  // velocity); fields.velocity where the model has none. The artificial
  // viscosity reads it too, so a model gives the wall's own velocity there
  // unless the wall is free-slip.
  const Vec3* viscous_velocity = nullptr;
  bool rigid_body = false;  // then `body` holds and the stage sums the reaction
  RigidBodyFrame body;
  // A model that keeps its wall particles in float (a scene of mixed
  // precision) gives their fields here, and `fields` stays empty.
  NeighboursF single_fields;
  const Vec3f* viscous_velocity_single = nullptr;

  bool in_single() const { return single_fields.density != nullptr; }
  // f(fields, viscous velocity) in the type the model keeps them in.
  template <class F>
  decltype(auto) visit_fields(F&& f) const {
    return in_single() ? f(single_fields, viscous_velocity_single) : f(fields, viscous_velocity);
  }
};

class TALUS_API SphBoundary : public Boundary {
 public:
  ~SphBoundary() override;

  // Registers wall fields, builds neighbour structures and the initial wall state.
  virtual void bind(World& world, const FluidSettings& settings) = 0;
  // Remembers the wall state at the start of a step.
  virtual void begin_step(World& world) = 0;
  // Wall-side passes at the current positions (the walls' own density rates,
  // the viscous velocity); returns the pair evaluations.
  virtual std::uint64_t fill_wall_state(World& /*world*/, const FluidView& /*fluid*/) { return 0; }
  // Points the wall sets at the store's current arrays and rebuilds their
  // grids at the current positions (other models may have grown the store,
  // a restart loads the positions); fill_wall_state does this too.
  virtual void refresh_wall_sets(World& /*world*/) {}
  // The model's wall sets, valid from refresh_wall_sets or fill_wall_state to the next advance_walls.
  virtual std::span<const WallSet> wall_sets() const { return {}; }
  // The fluid's force and torque on the rigid body of wall set `set`, summed by the stage's pass.
  virtual void take_reaction(World& /*world*/, std::size_t /*set*/, const Vec3& /*force*/, const Vec3& /*torque*/) {}
  // Forces that are not pair terms (penalty walls): added to the fluid's rates.
  virtual std::uint64_t add_direct_forces(World& /*world*/, const FluidView& /*fluid*/, const FluidRates& /*rates*/) {
    return 0;
  }
  // Moves the walls to `time` and advances their state by dt from the state
  // saved in begin_step with the rates of the last fill_wall_state().
  virtual void advance_walls(World& world, double time, double dt) = 0;
  // After the stage moved the fluid to `time`, the end of its step: a fluid
  // particle found inside the wall material has passed through the wall; the
  // model puts it back on the wall surface, takes away its velocity into the
  // wall, counts it once in World::wall_crossings and warns the first per wall.
  virtual void hold_fluid(World& /*world*/, double /*time*/) {}
  // Largest stable time step this model allows (a penalty stiffness), s.
  virtual double stable_time_step(const World& /*world*/) const { return std::numeric_limits<double>::infinity(); }
  // What `talus plan` lists for this model's own passes.
  virtual void describe_passes(StagePlan& plan) const = 0;
  // Whether the model works with a FluidView in float (FluidView::single). In
  // a scene of mixed precision the stage keeps the fluid in double unless
  // every wall model says so.
  virtual bool reads_single_fluid() const { return false; }
};

}  // namespace talus::sph
