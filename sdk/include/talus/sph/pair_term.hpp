// Pair terms as plugins (model kind "pair_term"): an SPH force or density
// term that a third party adds to the wcsph stage without forking it. The
// scene lists them under "pair_terms"; the stage calls each once per rate
// evaluation, after its own passes, and the term adds to the fluid's rates.
//
// A term plugin runs its own term struct (the contract of pair_loop.hpp)
// through sph::fluid_pass below, which is the SDK pair loop instantiated
// inside the plugin: a pair costs what a pair of a built-in term costs, and
// the one virtual call is per evaluation, never per pair. Each such term is
// its own neighbour traversal (as HOOMD's evaluators each run their own
// loop); the built-in terms stay fused in the stage's passes.
//
// A pair term acts between fluid particles only: it sees no wall sets, so it
// can never leave a reaction on a rigid body unaccounted.
#pragma once

#include <cstdint>
#include <limits>
#include <string>

#include "talus/plugin.hpp"
#include "talus/sph/boundary_pass.hpp"
#include "talus/sph/pair_loop.hpp"
#include "talus/world.hpp"

namespace talus::sph {

// What a term sees in one rate evaluation.
struct PairTermInput {
  const World& world;
  const FluidView& fluid;   // the fluid, its neighbour grid built on `position`
  const FluidRates& rates;  // add to these (never overwrite)
};

class TALUS_API PairTerm : public Model {
 public:
  ~PairTerm() override;

  // Once, at the stage's setup, after the fluid exists: register fields,
  // check materials (InputError with the JSON pointer).
  virtual void setup(World& /*world*/) {}
  // Adds the term's rates at the current state; returns the pair evaluations.
  virtual std::uint64_t add_rates(const PairTermInput& in) = 0;
  // Largest stable time step the term allows, s.
  virtual double stable_time_step(const World& /*world*/) const { return std::numeric_limits<double>::infinity(); }
  // One line for `talus plan`: what the pass computes.
  virtual std::string pass_description() const = 0;
};

// The term's pass: particle i of the fluid against its fluid neighbours j != i,
// start(i) -> Sums, terms' pair(p, sums) per neighbour, finish(i, sums). On
// several MPI ranks i runs over this rank's own particles only: the halo
// copies' rates are not wanted (their state comes from their owners).
template <class Start, class Finish, class... Terms>
std::uint64_t fluid_pass(const PairTermInput& in, Start&& start, Finish&& finish, const Terms&... terms) {
  const std::span<const Vec3> x = in.fluid.position;
  return pair_pass(in.world.fluid.owned_size(), x, *in.fluid.cells, in.world.kernel, same_set, start, finish,
                   terms...);
}

}  // namespace talus::sph
