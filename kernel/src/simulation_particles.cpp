// Per-step upkeep of the fluid particles: wrapping periodic axes and removing
// escaped particles, re-sorting them for locality, and stopping on non-finite values.
#include "simulation.hpp"

#include <algorithm>
#include <cmath>
#include <span>
#include <sstream>
#include <string>

#include "cell_order.hpp"
#include "talus/number_text.hpp"
#include "talus/error.hpp"

namespace talus {

void Simulation::remove_escaped_particles() {
  if (flag_escaped_particles() > 0) remove_flagged_particles();
}

// Halo rows are another rank's to wrap and remove: only the owned ones are looked at.
std::size_t Simulation::flag_escaped_particles() {
  ParticleStore& fluid = world_.fluid;
  const std::size_t n = fluid.owned_size();
  auto x = fluid.position();
  auto outside = [&](std::size_t i) {
    for (int a = 0; a < world_.dim; ++a)
      if (!world_.periodic[a] && (x[i][a] < world_.lo[a] || x[i][a] > world_.hi[a])) return true;
    return false;
  };
  std::size_t count = 0;
#pragma omp parallel for reduction(+ : count) schedule(static) if (n > 4096)
  for (std::size_t i = 0; i < n; ++i) {
    for (int a = 0; a < world_.dim; ++a) {
      const double L = world_.hi[a] - world_.lo[a];
      if (world_.periodic[a]) {
        if (x[i][a] < world_.lo[a]) x[i][a] += L;
        if (x[i][a] >= world_.hi[a]) x[i][a] -= L;
      }
    }
    count += outside(i);
  }
  // Flags only in the rare step in which a particle left: no byte per particle otherwise.
  escaped_.clear();
  if (count > 0) {
    escaped_.resize(n);
    for (std::size_t i = 0; i < n; ++i) escaped_[i] = outside(i);
  }
  return count;
}

void Simulation::remove_flagged_particles() {
  ParticleStore& fluid = world_.fluid;
  const std::size_t n = escaped_.size();
  if (n == 0) return;  // none left the domain
  const auto x = fluid.position();
  // The first particle of each body to leave, with where and when.
  removal_warned_.resize(world_.bodies.size(), 0);
  const auto body = fluid.body();
  const auto id = fluid.ids();
  for (std::size_t i = 0; i < n; ++i) {
    if (!escaped_[i] || removal_warned_[body[i]]) continue;
    removal_warned_[body[i]] = 1;
    world_.warnings.add("step " + std::to_string(world_.step) + " (t = " + fixed(world_.time, 6) +
                        " s): fluid particle " + std::to_string(id[i]) + " of body '" + world_.bodies[body[i]].name +
                        "' left the domain at " + vec_text(x[i], world_.dim) +
                        " and was removed (an open face, or a leak through a wall); the summary counts all removals");
  }
  world_.removed += fluid.remove_if(escaped_);
  escaped_ = {};
  world_.refresh_material_index();
}

void Simulation::resort_particles() {
  if (world_.fluid.size() == 0) return;
  const double cell = world_.h > 0 ? world_.kernel.support_radius() : 2.0 * world_.dp;
  if (!(cell > 0)) return;
  world_.release_material_index();
  world_.fluid.reorder(cell_order(world_.fluid.position(), world_.lo, world_.hi, cell, world_.dim));
  world_.refresh_material_index();
}

void Simulation::check_finite() const {
  const ParticleStore& f = world_.fluid;
  const std::size_t n = f.owned_size();
  const auto x = f.position();
  // The first non-finite row of each start-state field the stages read (a
  // run-out scene has no pressure), each in the type it is stored in.
  auto first_bad = [&](auto column, auto finite) {
    std::size_t bad = n;
#pragma omp parallel for reduction(min : bad) schedule(static) if (n > 4096)
    for (std::size_t i = 0; i < n; ++i)
      if (!finite(column[i])) bad = std::min(bad, i);
    return bad;
  };
  auto finite_vector = [](const auto& v) { return is_finite(v); };
  auto finite_scalar = [](auto v) { return std::isfinite(v); };
  std::size_t bad = first_bad(x, finite_vector);
  const char* what = "position";
  auto check = [&](const char* name, std::size_t found) {
    if (found < bad) {
      bad = found;
      what = name;
    }
  };
  if (f.has("velocity")) f.visit_vector("velocity", [&](auto u) { check("velocity", first_bad(u, finite_vector)); });
  for (const char* name : {"density", "pressure"})
    if (f.has(name)) f.visit_scalar(name, [&](auto v) { check(name, first_bad(v, finite_scalar)); });
  if (bad == n) return;
  const int body = f.body()[bad];
  std::ostringstream msg;
  msg << "error: step " << world_.step << " (t = " << fixed(world_.time, 6) << " s): particle " << f.ids()[bad]
      << " of body '" << world_.bodies[body].name << "' at " << vec_text(x[bad], world_.dim) << " has non-finite " << what
      << "\n       last good output: " << last_output() << "; stopping.";
  throw RunError(msg.str());
}

}  // namespace talus
