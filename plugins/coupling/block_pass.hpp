// The fluid-block pair pass: fluid particles i near one block gather the
// pair terms of that block's boundary particles (same terms as fluid-fluid),
// and the pass sums the reaction on the block (sph::reducing_pair_pass:
// per-thread partials added in thread order, deterministic for a given thread
// count). Fluid particles outside the block's bounding box padded by the
// kernel support are skipped before any neighbour search.
//
// Reaction: the force on i from the block is m_i a_i(block); the block gets
// -m_i a_i. Its torque about the centroid X sums (x_b - X) x (-m_i a_ib) over
// pairs = (x_i - X) x (-m_i a_i) + m_i sum_b dx_ib x a_ib (dx = x_i - x_b), so
// non-central (viscous) pair forces contribute their exact moment too
// (sph::WithPairMoment).
//
// Periodic axes: a block may straddle a periodic boundary (the dda stage does
// not wrap blocks), so x_i - X is taken as its minimum image (period > 0 on
// periodic axes), both for the lever arm and for the bounding-box filter:
// fluid across the boundary from the centroid still acts, about the image of
// the centroid it is near.
#pragma once

#include <algorithm>
#include <cstdint>
#include <span>

#include "block_link.hpp"
#include "talus/kernel_table.hpp"
#include "talus/sph/boundary_pass.hpp"
#include "talus/sph/fluid_terms.hpp"
#include "talus/sph/neighbour_grid.hpp"
#include "talus/sph/pair_loop.hpp"

namespace talus::coupling {

// The fluid's force and torque (about the centroid) on one block.
struct BlockReaction {
  Vec3 force, torque;
  BlockReaction& operator+=(const BlockReaction& o) {
    force += o.force;
    torque += o.torque;
    return *this;
  }
};

struct BlockPassInput {
  const sph::FluidView& fluid;
  const sph::FluidRates& rates;
  const sph::NeighbourGrid& cells;  // on xb
  std::span<const Vec3> xb;         // the block's particles
  const KernelTable& kernel;
  Vec3 lo, hi;                      // block bounding box
  Vec3 centre;                      // block centroid
  Vec3 period;                      // domain length on periodic axes, 0 on closed ones
  const double* mu;                 // viscosity per material (where the fluid has no mu_eff)
  bool continuity;
};

template <class... Terms>
BlockReaction block_pass(const BlockPassInput& in, std::uint64_t& pairs, const Terms&... terms) {
  struct Sums : sph::FluidSums {
    Vec3 moment;  // sum over pairs of dx x (pair acceleration)
  };
  const double radius = in.kernel.support_radius();
  const Vec3 lo = in.lo - Vec3{radius, radius, radius}, hi = in.hi + Vec3{radius, radius, radius};
  const auto& f = in.fluid;
  auto arm_of = [&](Index i) { return minimum_image(f.position[i] - in.centre, in.period); };  // lever arm
  auto skip = [&](Index i) {
    const Vec3 xi = in.centre + arm_of(i);  // the image near the block
    return xi.x < lo.x || xi.y < lo.y || xi.z < lo.z || xi.x > hi.x || xi.y > hi.y || xi.z > hi.z;
  };
  auto start = [&](Index i) {
    Sums s;
    s.v = f.velocity[i];
    s.rho = f.density[i];
    s.inv_rho = 1.0 / s.rho;
    s.p = f.pressure[i];
    s.c = f.sound_speed[i];
    s.mu = f.viscosity.empty() ? in.mu[f.material[i]] : f.viscosity[i];  // mu_eff, as against walls
    return s;
  };
  auto finish = [&](Index i, const Sums& s, BlockReaction& on_block) {
    in.rates.acceleration[i] += s.acc;
    if (in.continuity) in.rates.density_rate[i] += s.drho;
    in.rates.visc_rate[i] = std::max(in.rates.visc_rate[i], s.visc);
    const double mi = f.mass[i];
    const Vec3 force = s.acc * (-mi);
    on_block.force += force;
    on_block.torque += cross(arm_of(i), force) + s.moment * mi;
  };
  return sph::reducing_pair_pass<BlockReaction>(f.position.size(), f.position, in.cells, in.xb, in.kernel,
                                                sph::other_set, pairs, skip, start, finish,
                                                sph::with_pair_moment(terms...));
}

}  // namespace talus::coupling
