// Time integration of the wcsph stage. Every scheme updates the fluid, asks
// each wall model to follow (advance_walls), and recomputes the pressure with
// one EOS call per material.
#include <algorithm>

#include "fluid_fields.hpp"
#include "talus/world.hpp"
#include "wcsph_stage.hpp"

namespace talus::wcsph {

// Explicit Euler of the rock-fluid seed (eqs. 20-21): v^{n+1} = v^n + dt a^n,
// x^{n+1} = x^n + dt v^{n+1} (semi-implicit), rho^{n+1} = rho^n + dt D^n.
void WcsphStage::step_euler(World& world, double dt) {
  const bool cont = density_ == DensityMode::continuity;
  for (sph::SphBoundary* wall : walls_) wall->begin_step(world);
  with_fluid_fields(world.fluid, [&](auto f) {
#pragma omp parallel for schedule(static) if (f.x.size() >= 4096)
    for (std::size_t i = 0; i < f.x.size(); ++i) {
      const Vec3 v = Vec3(f.v[i]) + f.a[i] * dt;
      f.v[i] = v;
      f.x[i] += v * dt;
      if (cont) f.rho[i] += f.drho[i] * dt;
    }
  });
  for (sph::SphBoundary* wall : walls_) wall->advance_walls(world, world.time + dt, dt);
  if (cont) update_pressure(world);
}

namespace {

// One Verlet update of every fluid particle; the fields, v_prev and rho_prev
// in the types they are stored in (float under mixed precision). The loop is
// the same code for double as a loop over plain spans.
template <class Fields, class SavedVelocity, class SavedDensity>
void verlet_update(Fields f, std::span<SavedVelocity> v_prev, std::span<SavedDensity> rho_prev, double dt,
                   bool corrective, bool cont) {
  const double half_dt2 = 0.5 * dt * dt;
#pragma omp parallel for schedule(static) if (f.x.size() >= 4096)
  for (std::size_t i = 0; i < f.x.size(); ++i) {
    const Vec3 v_n = f.v[i];
    const double rho_n = f.rho[i];
    f.x[i] += v_n * dt + f.a[i] * half_dt2;
    if (corrective) {
      f.v[i] = v_n + f.a[i] * dt;
      if (cont) f.rho[i] = rho_n + f.drho[i] * dt;
    } else {
      f.v[i] = Vec3(v_prev[i]) + f.a[i] * (2.0 * dt);
      if (cont) f.rho[i] = rho_prev[i] + f.drho[i] * (2.0 * dt);
    }
    v_prev[i] = v_n;
    rho_prev[i] = static_cast<SavedDensity>(rho_n);
  }
}

}  // namespace

// Verlet (Verlet 1967, as in DualSPHysics): one force evaluation per step,
//   v^{n+1} = v^{n-1} + 2 dt a^n,  rho^{n+1} = rho^{n-1} + 2 dt D^n,
//   x^{n+1} = x^n + dt v^n + dt^2/2 a^n,
// and every `verlet_steps` steps (and the first) the corrective step
//   v^{n+1} = v^n + dt a^n,  rho^{n+1} = rho^n + dt D^n
// that stops the odd and even steps from drifting apart.
void WcsphStage::step_verlet(World& world, double dt) {
  const bool cont = density_ == DensityMode::continuity;
  const bool corrective = verlet_counter_ % static_cast<std::uint64_t>(verlet_steps_) == 0;
  ++verlet_counter_;
  for (sph::SphBoundary* wall : walls_) wall->begin_step(world);
  with_fluid_fields(world.fluid, [&](auto f) {
    world.fluid.visit_vector("velocity_prev", [&](auto v_prev) {
      world.fluid.visit_scalar("density_prev",
                               [&](auto rho_prev) { verlet_update(f, v_prev, rho_prev, dt, corrective, cont); });
    });
  });
  for (sph::SphBoundary* wall : walls_) wall->advance_walls(world, world.time + dt, dt);
  if (cont) update_pressure(world);
}

// Symplectic position-Verlet (Leimkuhler; DualSPHysics "Symplectic") and the
// predictor-corrector of Monaghan (1989) that the coastline seed uses. Both:
//   predictor: x = x^n + dt/2 v^n, v = v^n + dt/2 a^n, rho = rho^n + dt/2 D^n
//   rates at n+1/2
//   corrector: v^{n+1} = v^n + dt a^{n+1/2}, x^{n+1} = x^n + dt/2 (v^n + v^{n+1})
// and for the density, symplectic: rho^{n+1} = rho^n (2 - eps)/(2 + eps) with
// eps = -(D^{n+1/2}/rho^{n+1/2}) dt; predictor-corrector: rho^n + dt D^{n+1/2}.
void WcsphStage::step_two_stage(World& world, double dt) {
  const bool cont = density_ == DensityMode::continuity;
  const bool symplectic = integrator_ == Integrator::symplectic;
  const double half = 0.5 * dt;
  // f(v_n, rho_n): the state at t^n in the type it is stored in (float under mixed precision).
  auto with_state_n = [&](auto&& f) {
    world.fluid.visit_vector("velocity_n",
                             [&](auto v_n) { world.fluid.visit_scalar("density_n", [&](auto rho_n) { f(v_n, rho_n); }); });
  };
  {
    auto x_n = world.fluid.vector("position_n");
    for (sph::SphBoundary* wall : walls_) wall->begin_step(world);
    with_state_n([&](auto v_n, auto rho_n) {
      with_fluid_fields(world.fluid, [&](auto f) {
#pragma omp parallel for schedule(static) if (f.x.size() >= 4096)
        for (std::size_t i = 0; i < f.x.size(); ++i) {
          const Vec3 v = f.v[i];
          x_n[i] = f.x[i];
          v_n[i] = v;
          rho_n[i] = static_cast<typename decltype(rho_n)::value_type>(f.rho[i]);
          f.x[i] += v * half;
          f.v[i] = v + f.a[i] * half;
          if (cont) f.rho[i] += f.drho[i] * half;
        }
      });
    });
    for (sph::SphBoundary* wall : walls_) wall->advance_walls(world, world.time + half, half);
    if (cont) update_pressure(world);
  }
  compute_rates(world);
  auto x_n = world.fluid.vector("position_n");
  with_state_n([&](auto v_n, auto rho_n) {
    with_fluid_fields(world.fluid, [&](auto f) {
#pragma omp parallel for schedule(static) if (f.x.size() >= 4096)
      for (std::size_t i = 0; i < f.x.size(); ++i) {
        const Vec3 v_start = v_n[i];
        const Vec3 v_end = v_start + f.a[i] * dt;
        f.v[i] = v_end;
        f.x[i] = x_n[i] + (v_start + v_end) * half;
        if (cont) {
          if (symplectic) {
            const double eps = -static_cast<double>(f.drho[i]) / f.rho[i] * dt;
            f.rho[i] = rho_n[i] * (2.0 - eps) / (2.0 + eps);
          } else {
            f.rho[i] = rho_n[i] + f.drho[i] * dt;
          }
        }
      }
    });
  });
  for (sph::SphBoundary* wall : walls_) wall->advance_walls(world, world.time + dt, dt);
  if (cont) update_pressure(world);
}

}  // namespace talus::wcsph
