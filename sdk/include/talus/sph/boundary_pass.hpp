// The fluid-wall interaction pass of the wcsph stage (DESIGN.md: "Boundaries
// are separate interaction passes with their own neighbour lists and batch
// hooks that fill wall state"). A boundary model for SPH fluid derives from
// SphBoundary; the stage makes one virtual call per hook per (sub)step, never
// one per pair, and the fluid-fluid force terms never branch on the boundary.
//
// Call order in one stage substep (every integrator):
//   begin_step(world)                      once per step, state at t^n
//   interact(world, fluid, rates)          rates at the current state: the model adds
//                                          its forces and density rates to the fluid's
//                                          and computes its walls' own rates
//   advance_walls(world, t, dt)            wall state at time t = t^n + dt from the
//                                          state saved by begin_step and the last rates
// With summation density the stage also calls add_density(world, fluid, rho) before
// the force pass, to add the walls' share of rho_i = sum_j m_j W_ij.
#pragma once

#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "talus/boundary.hpp"
#include "talus/sph/fluid_terms.hpp"
#include "talus/sph/neighbour_grid.hpp"
#include "talus/kernel_table.hpp"
#include "talus/stage.hpp"
#include "talus/vec3.hpp"

namespace talus {
class World;
}

namespace talus::sph {

enum class ViscosityModel { artificial, laminar, laplacian };

// What the stage tells its boundaries once, at its setup (after every
// boundary's Boundary::setup has run and the fluid exists).
struct FluidSettings {
  const KernelTable* kernel = nullptr;
  ViscosityModel viscosity = ViscosityModel::artificial;
  double alpha = 0.01;                  // artificial viscosity coefficient
  std::vector<double> material_mu;      // dynamic viscosity per material, Pa s (laminar)
  bool summation_density = false;
  Vec3 lo, hi;                          // bounds the fluid cell list covers
  // True when FluidView::viscosity carries mu_eff per particle (non-Newtonian
  // rheology or eddy viscosity); material_mu then holds each material's
  // reference viscosity only.
  bool per_particle_viscosity = false;
};

// Read-only view of the fluid for one pass; `cells` is the fluid's cell list,
// built on `position`.
struct FluidView {
  const NeighbourGrid* cells = nullptr;
  std::span<const Vec3> position, velocity;
  std::span<const double> density, pressure, sound_speed, mass;
  std::span<const std::int32_t> material;
  // Apparent viscosity mu_eff per fluid particle (Pa s) when the stage runs the
  // three-pass non-Newtonian / turbulent viscosity; empty otherwise (then
  // FluidSettings::material_mu holds). A wall's laminar term should then use
  // mu_eff[i] for the fluid particle i (no-slip: mu_wall = mu_i).
  std::span<const double> viscosity;
  std::span<const double> inv_density;  // 1/rho per fluid particle (continuity of a wall against the fluid)

  // The fluid as the neighbour set of a wall-side pass.
  Neighbours neighbours() const {
    return {velocity.data(), density.data(),     pressure.data(), sound_speed.data(), mass.data(),
            material.data(), inv_density.data(), nullptr /* rho/c^2 */, viscosity.data()};
  }
};

// The fluid's rates; a boundary adds to them (never overwrites).
struct FluidRates {
  std::span<Vec3> acceleration;     // m/s^2
  std::span<double> density_rate;   // kg/m^3/s (continuity; unused with summation density)
  std::span<double> visc_rate;      // 1/s, max |v_ij.x_ij|/(r^2+eta^2) for the time-step bound
};

class TALUS_API SphBoundary : public Boundary {
 public:
  ~SphBoundary() override;

  // Registers wall fields, builds neighbour structures and the initial wall state.
  virtual void bind(World& world, const FluidSettings& settings) = 0;
  // Remembers the wall state at the start of a step.
  virtual void begin_step(World& world) = 0;
  // Adds the walls' forces and density rates to the fluid and computes the
  // walls' own rates, at the current positions.
  virtual void interact(World& world, const FluidView& fluid, const FluidRates& rates) = 0;
  // Summation density: adds sum_b m_b W_ib over wall particles b to rho[i].
  virtual void add_density(const World& world, const FluidView& fluid, std::span<double> rho) = 0;
  // Moves the walls to `time` and advances their state by dt from the state
  // saved in begin_step with the rates of the last interact().
  virtual void advance_walls(World& world, double time, double dt) = 0;
  // Largest stable time step this model allows (a penalty stiffness), s.
  virtual double stable_time_step(const World& /*world*/) const { return std::numeric_limits<double>::infinity(); }
  // Pair evaluations of the last interact(), for throughput reports.
  virtual std::uint64_t pair_count() const { return 0; }
  // What `talus plan` lists for this model.
  virtual void describe_passes(StagePlan& plan) const = 0;
};

}  // namespace talus::sph
