// The fluid-block pair pass: fluid particles i near one block gather the
// pair terms of that block's boundary particles (same terms as fluid-fluid),
// and the pass sums the reaction on the block. Per-thread partial sums, added
// in thread order by the caller, keep the result deterministic for a given
// thread count. Fluid particles outside the block's bounding box padded by
// the kernel support are skipped before any neighbour search.
//
// Reaction: the force on i from the block is m_i a_i(block); the block gets
// -m_i a_i. Its torque about the centroid X sums (x_b - X) x (-m_i a_ib) over
// pairs = (x_i - X) x (-m_i a_i) + m_i sum_b dx_ib x a_ib (dx = x_i - x_b), so
// non-central (viscous) pair forces contribute their exact moment too.
//
// Periodic axes: a block may straddle a periodic boundary (the dda stage does
// not wrap blocks), so x_i - X is taken as its minimum image (period_ > 0 on
// periodic axes), both for the lever arm and for the bounding-box filter:
// fluid across the boundary from the centroid still acts, about the image of
// the centroid it is near.
#pragma once

#include <cmath>
#include <cstdint>
#include <span>

#include <omp.h>

#include "block_link.hpp"
#include "talus/sph/neighbour_grid.hpp"
#include "talus/kernel_table.hpp"
#include "talus/sph/boundary_pass.hpp"
#include "talus/sph/fluid_terms.hpp"

namespace talus::coupling {

struct BlockPassInput {
  const sph::FluidView& fluid;
  const sph::FluidRates& rates;
  const sph::NeighbourGrid& cells;  // on xb
  std::span<const Vec3> xb;     // the block's particles
  const KernelTable& kernel;
  Vec3 lo, hi;                  // block bounding box
  Vec3 centre;                  // block centroid
  Vec3 period;                  // domain length on periodic axes, 0 on closed ones
  const double* mu;             // viscosity per material
  bool continuity;
  Vec3* thread_force;           // out: per-thread partial force on the block
  Vec3* thread_torque;          // out: per-thread partial torque about the centroid
};

template <class... Terms>
std::uint64_t block_pass(const BlockPassInput& in, const Terms&... terms) {
  const double radius = in.kernel.support_radius();
  const double eta2 = 0.01 * in.kernel.h() * in.kernel.h();
  const Vec3 lo = in.lo - Vec3{radius, radius, radius}, hi = in.hi + Vec3{radius, radius, radius};
  const auto& f = in.fluid;
  const std::int64_t n = static_cast<std::int64_t>(f.position.size());
  const int threads = omp_get_max_threads();
  for (int t = 0; t < threads; ++t) in.thread_force[t] = in.thread_torque[t] = Vec3{};
  std::uint64_t pairs = 0;
#pragma omp parallel reduction(+ : pairs)
  {
    Vec3 force{}, torque{};
#pragma omp for schedule(static)
    for (std::int64_t ii = 0; ii < n; ++ii) {
      const auto i = static_cast<Index>(ii);
      const Vec3 arm = minimum_image(f.position[i] - in.centre, in.period);  // lever arm about the centroid
      const Vec3 xi = in.centre + arm;                                         // the image near the block
      if (xi.x < lo.x || xi.y < lo.y || xi.z < lo.z || xi.x > hi.x || xi.y > hi.y || xi.z > hi.z) continue;
      sph::FluidSums s;
      s.v = f.velocity[i];
      s.rho = f.density[i];
      s.inv_rho = 1.0 / s.rho;
      s.p = f.pressure[i];
      s.c = f.sound_speed[i];
      s.mu = in.mu[f.material[i]];
      Vec3 moment{};
      std::uint64_t count = 0;
      in.cells.for_each_neighbour(f.position[i], in.xb, radius, [&](Index j, const Vec3& dx, double r2) {
        sph::Pair q;
        q.j = j;
        q.dx = dx;
        q.r2 = r2;
        q.r = std::sqrt(r2);
        q.w = in.kernel.w(q.r);
        q.dw_r = in.kernel.dw_over_r_from_r2(r2);
        q.inv_r2e = 1.0 / (r2 + eta2);
        const Vec3 before = s.acc;
        (terms.pair(q, s), ...);
        moment += cross(dx, s.acc - before);
        ++count;
      });
      if (count == 0) continue;
      pairs += count;
      in.rates.acceleration[i] += s.acc;
      if (in.continuity) in.rates.density_rate[i] += s.drho;
      in.rates.visc_rate[i] = std::max(in.rates.visc_rate[i], s.visc);
      const double mi = f.mass[i];
      const Vec3 on_block = s.acc * (-mi);
      force += on_block;
      torque += cross(arm, on_block) + moment * mi;
    }
    in.thread_force[omp_get_thread_num()] = force;
    in.thread_torque[omp_get_thread_num()] = torque;
  }
  return pairs;
}

}  // namespace talus::coupling
