// The symmetric (mutual) form of the fused pair loop for a pass of one set
// against itself: each pair is evaluated once, from the particle earlier in
// the grid's sorted order, and gives its contribution to both particles.
// Pressure, viscosity, continuity and diffusion are antisymmetric or symmetric
// in i and j, so the shared factors (kernel gradient, pressure sum, v_ij . x_ij)
// are computed half as often as in the gather pass of pair_loop.hpp.
//
// Particle i keeps its own sums in registers (Sums, as in a gather pass); what
// it gives its later neighbours j goes to its thread's FluidReactions. Thread
// 0 writes into the pass's output arrays, every other thread into a buffer of
// its own, and the buffers are added to the output in thread order after the
// scan: no atomics, and the same result in every run at a given thread count
// (a fixed split of the sorted slots; DESIGN.md principle 8).
//
// A mutual term has, besides its gather pair(q, s), a
//   template <class S, class R> void mutual(const Pair& q, S& s, R& r) const
// that adds i's share to s and j's (q.j) to r, a PairReaction the pass adds
// to j once all terms of the pair have run (one store per pair, not per term).
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include <omp.h>

#include "talus/config.hpp"
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
  void clear(std::size_t n) const {
    std::fill(acc, acc + n, Vec3{});
    std::fill(drho, drho + n, 0.0);
    std::fill(visc, visc + n, 0.0);
  }
};

// The reaction buffers of threads 1, 2, ...: kept by the stage between
// passes, so nothing allocates once sized for the particle and thread count.
class ReactionBuffers {
 public:
  // Buffers for `threads` threads (thread 0 needs none) of n particles each.
  void reserve(int threads, std::size_t n) {
    const std::size_t extra = threads > 1 ? static_cast<std::size_t>(threads - 1) : 0;
    if (acc_.size() < extra) {
      acc_.resize(extra);
      drho_.resize(extra);
      visc_.resize(extra);
    }
    for (std::size_t t = 0; t < extra; ++t) {
      if (acc_[t].size() < n) {
        acc_[t].resize(n);
        drho_[t].resize(n);
        visc_[t].resize(n);
      }
    }
  }
  // Thread t's buffer (t >= 1).
  FluidReactions thread(int t) {
    const std::size_t k = static_cast<std::size_t>(t - 1);
    return {acc_[k].data(), drho_[k].data(), visc_[k].data()};
  }

 private:
  std::vector<std::vector<Vec3>> acc_;
  std::vector<std::vector<double>> drho_, visc_;
};

// Runs the mutual pass over every point binned in `cells` (set A = set B).
// start(i) -> Sums (with acc, drho, visc zero), every term's mutual() per
// pair, then out = the sum over pairs for every particle, and finish(i) once
// out holds particle i's total. Points from `owned` on are halo copies of
// another MPI rank's particles (talus/parallel.hpp): their totals are not
// wanted, so pairs of two of them are skipped, and only their pairs with
// owned points count. Returns the number of particle-neighbour evaluations
// (twice the pairs), as a gather pass would count them.
template <class Start, class Finish, class... Terms>
std::uint64_t mutual_pair_pass(const NeighbourGrid& cells, const KernelTable& kernel, FluidReactions out,
                               ReactionBuffers& buffers, std::size_t owned, Start&& start, Finish&& finish,
                               const Terms&... terms) {
  constexpr bool need_value = (Terms::uses_value || ...);
  constexpr bool need_gradient = (Terms::uses_gradient || ...);
  const std::span<const Index> order = cells.order();
  const std::size_t n = order.size();
  const double radius = kernel.support_radius();
  const double eta2 = pair_eta2(kernel.h());
  const int threads = n >= parallel_min ? omp_get_max_threads() : 1;
  buffers.reserve(threads, n);
  std::uint64_t pairs = 0;
#pragma omp parallel num_threads(threads) reduction(+ : pairs)
  {
    const int t = omp_get_thread_num(), used = omp_get_num_threads();
    FluidReactions mine = t == 0 ? out : buffers.thread(t);
    mine.clear(n);
#pragma omp barrier
    // Chunks dealt round-robin: the free surface (fewer neighbours) is shared
    // out instead of falling to one thread, and the split is still fixed.
#pragma omp for schedule(static, 512)
    for (std::int64_t ss = 0; ss < static_cast<std::int64_t>(n); ++ss) {
      const std::size_t slot = static_cast<std::size_t>(ss);
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
        mine.add(j, rj.acc, rj.drho, rj.visc);
      });
      mine.add(i, sums.acc, sums.drho, sums.visc);
      pairs += 2 * count;
    }
    // The implicit barrier above: every buffer is complete.
#pragma omp for schedule(static)
    for (std::int64_t kk = 0; kk < static_cast<std::int64_t>(n); ++kk) {
      const Index k = static_cast<Index>(kk);
      for (int u = 1; u < used; ++u) {
        const FluidReactions other = buffers.thread(u);
        out.add(k, other.acc[k], other.drho[k], other.visc[k]);
      }
      finish(k);
    }
  }
  return pairs;
}

}  // namespace talus::sph
