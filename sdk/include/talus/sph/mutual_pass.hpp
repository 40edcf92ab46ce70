// The symmetric (mutual) form of the fused pair loop for a pass of one set
// against itself: each pair is evaluated once, from the particle earlier in
// the grid's sorted order, and gives its contribution to both particles.
// Pressure, viscosity, continuity and diffusion are antisymmetric or symmetric
// in i and j, so the shared factors (kernel gradient, pressure sum, v_ij . x_ij)
// are computed half as often as in the gather pass of pair_loop.hpp.
//
// Particle i keeps its own sums in registers (Sums, as in a gather pass) and
// adds what it gives its later neighbours j straight into the pass's output.
// Threads take the grid's write blocks (neighbour_grid.hpp) one colour after
// the other, so no two threads ever write to the same particle: no atomics,
// no per-thread copies of the output, and every particle receives its shares
// in an order fixed by the cells, the same on any number of threads (DESIGN.md
// principle 8).
//
// A mutual term has, besides its gather pair(q, s), a
//   template <class S, class R> void mutual(const Pair& q, S& s, R& r) const
// that adds i's share to s and j's (q.j) to r, a PairReaction the pass adds
// to j once all terms of the pair have run (one store per pair, not per term).
#pragma once

#include <algorithm>
#include <cstdint>

#include <omp.h>

#include "talus/config.hpp"
#include "talus/error.hpp"
#include "talus/kernel_table.hpp"
#include "talus/neighbour_grid.hpp"
#include "talus/sph/pair_loop.hpp"
#include "talus/vec3.hpp"

namespace talus::sph {

// What one pair gives its later particle j (a maximum for visc).
struct PairReaction {
  Vec3 acc;
  double drho = 0.0;
  double visc = 0.0;
};

// Per-particle accumulators of a force pass: acceleration, density rate, and
// the largest |v_ij . x_ij|/(r^2 + eta^2) (a maximum, not a sum).
struct FluidReactions {
  Vec3* acc = nullptr;
  double* drho = nullptr;
  double* visc = nullptr;
  TALUS_PAIR_INLINE void add(Index k, const Vec3& a, double d, double v) const {
    acc[k] += a;
    drho[k] += d;
    visc[k] = std::max(visc[k], v);
  }
  void clear_one(Index k) const {
    acc[k] = Vec3{};
    drho[k] = 0.0;
    visc[k] = 0.0;
  }
};

// Runs the mutual pass over every point binned in `cells` (set A = set B; a
// grid of one level whose radius() covers the kernel's support). start(i) ->
// Sums (with acc, drho, visc zero), every term's mutual() per pair, then out =
// the sum over pairs for every particle, and finish(i) once out holds
// particle i's total. Points from `owned` on are halo copies of another MPI
// rank's particles (talus/parallel.hpp): their totals are not wanted, so
// pairs of two of them are skipped, and only their pairs with owned points
// count. Returns the number of particle-neighbour evaluations (twice the
// pairs), as a gather pass would count them.
template <class Start, class Finish, class... Terms>
std::uint64_t mutual_pair_pass(const NeighbourGrid& cells, const KernelTable& kernel, FluidReactions out,
                               std::size_t owned, Start&& start, Finish&& finish, const Terms&... terms) {
  constexpr bool need_value = (Terms::uses_value || ...);
  constexpr bool need_gradient = (Terms::uses_gradient || ...);
  const std::span<const Index> order = cells.order();
  const std::size_t n = order.size();
  const double radius = kernel.support_radius();
  if (radius > cells.radius())
    throw RunError("mutual pair pass: the kernel's support exceeds the neighbour grid's search radius");
  const double eta2 = pair_eta2(kernel.h());
  const int threads = n >= parallel_min ? omp_get_max_threads() : 1;
  std::uint64_t pairs = 0;
  auto pairs_from = [&](std::size_t slot) {
    const Index i = order[slot];
    auto sums = start(i);
    std::uint64_t count = 0;
    const bool halo_i = i >= owned;
    // One traversal for both kinds of i (not two inlined copies, whose
    // floating-point code could differ): the owned rates stay bit for bit.
    cells.for_each_later_neighbour(slot, radius, [&](Index j, const Vec3& dx, double r2)
                                                     __attribute__((always_inline)) {
      if (halo_i && j >= owned) return;
      Pair p;
      p.j = j;
      p.dx = dx;
      p.r2 = r2;
      if constexpr (need_value) {
        p.r = std::sqrt(r2);
        p.w = kernel.w(p.r);
      }
      if constexpr (need_gradient) {
        p.dw_r = kernel.dw_over_r_from_r2(r2);
        p.inv_r2e = 1.0 / (r2 + eta2);
      }
      ++count;
      PairReaction rj;
      (terms.mutual(p, sums, rj), ...);
      out.add(j, rj.acc, rj.drho, rj.visc);
    });
    out.add(i, sums.acc, sums.drho, sums.visc);
    return 2 * count;
  };
#pragma omp parallel num_threads(threads) reduction(+ : pairs)
  {
#pragma omp for schedule(static)
    for (std::int64_t k = 0; k < static_cast<std::int64_t>(n); ++k) out.clear_one(static_cast<Index>(k));
    for (int colour = 0; colour < cells.write_colours(); ++colour) {
      // Blocks hold very different numbers of particles (a free surface, a
      // collapsing column): dealt one at a time to whichever thread is free.
#pragma omp for schedule(dynamic, 1)
      for (std::int64_t b = 0; b < static_cast<std::int64_t>(cells.write_blocks(colour)); ++b)
        cells.for_each_write_block_run(colour, static_cast<std::size_t>(b), [&](std::size_t begin, std::size_t end) {
          for (std::size_t slot = begin; slot < end; ++slot) pairs += pairs_from(slot);
        });
    }
#pragma omp for schedule(static)
    for (std::int64_t k = 0; k < static_cast<std::int64_t>(n); ++k) finish(static_cast<Index>(k));
  }
  return pairs;
}

}  // namespace talus::sph
