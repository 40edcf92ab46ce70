// The fused SPH pair loop (DESIGN.md, "Fast loops"): one neighbour traversal
// per pass, the per-pair quantities (dx, r, W, dW/dr) computed once and handed
// to every term of the pass. Terms are plain structs whose pair() inlines into
// the traversal: no virtual call, no allocation, no lookup by name.
//
// A pass is gather-style: particle i of set A sums over its neighbours j of
// set B (A and B may be the same set), so every particle writes only its own
// results: parallel over i without atomics, and deterministic whatever the
// thread count (DESIGN.md principle 8).
//
//   struct MySums { Vec3 v; double rho; Vec3 acc; };     // i-state and sums
//   auto start  = [&](Index i) { return MySums{vel[i], rho[i], {}}; };
//   auto finish = [&](Index i, const MySums& s) { acc[i] = s.acc; };
//   sph::pair_pass(n, pos, cells, pos, kernel, sph::same_set, start, finish,
//                  sph::PressureForce{...}, sph::Continuity{...});
//
// A term is any type with `static constexpr bool uses_value, uses_gradient`
// and `template <class Sums> void pair(const sph::Pair&, Sums&) const`.
#pragma once

#include <cmath>
#include <cstdint>
#include <span>
#include <tuple>

#include "talus/cell_list.hpp"
#include "talus/sph/neighbour_grid.hpp"
#include "talus/config.hpp"
#include "talus/kernel_table.hpp"
#include "talus/vec3.hpp"

namespace talus::sph {

// The per-pair quantities every term of a pass shares.
struct Pair {
  Index j = 0;       // neighbour index in set B
  Vec3 dx;           // x_i - x_j (minimum image on periodic axes)
  double r2 = 0.0;   // |dx|^2
  double r = 0.0;    // |dx|, filled when a term uses_value
  double w = 0.0;    // W(r), filled when a term uses_value
  double dw_r = 0.0; // (dW/dr)/r, filled when a term uses_gradient: grad_i W_ij = dx * dw_r
  double inv_r2e = 0.0;  // 1/(r^2 + eta^2), eta = 0.1 h (the usual regularisation), with the gradient
  Vec3 grad() const { return dx * dw_r; }
};

// Below this many particles a loop runs on one thread: a parallel region
// costs more than it saves there (and much more on a loaded machine, where a
// barrier waits for a descheduled thread).
inline constexpr std::size_t parallel_min = 4096;

// Whether set A and set B are the same particles (then j == i is skipped).
enum class Sets { same, different };
inline constexpr Sets same_set = Sets::same;
inline constexpr Sets other_set = Sets::different;

namespace detail {
template <class Sums, class... Terms>
TALUS_PAIR_INLINE void apply_terms(const Pair& p, Sums& sums, const Terms&... terms) {
  (terms.pair(p, sums), ...);
}
}  // namespace detail

// Runs the fused pass over particles i in [0, n) of set A (positions xa)
// against the neighbours in `cells` (built on positions xb of set B).
// start(i) -> Sums, every term's pair(p, sums) per neighbour, finish(i, sums).
// Returns the number of pair evaluations (for throughput reports).
// `Grid` is sph::NeighbourGrid or talus::CellList (same query contract).
template <class Grid, class Start, class Finish, class... Terms>
std::uint64_t pair_pass(std::size_t n, std::span<const Vec3> xa, const Grid& cells, std::span<const Vec3> xb,
                        const KernelTable& kernel, Sets sets, Start&& start, Finish&& finish, const Terms&... terms) {
  constexpr bool need_value = (Terms::uses_value || ...);
  constexpr bool need_gradient = (Terms::uses_gradient || ...);
  const double radius = kernel.support_radius();
  const double eta2 = 0.01 * kernel.h() * kernel.h();
  const bool skip_self = sets == Sets::same;
  std::uint64_t pairs = 0;
#pragma omp parallel for schedule(dynamic, 128) reduction(+ : pairs) if (n >= parallel_min)
  for (std::int64_t ii = 0; ii < static_cast<std::int64_t>(n); ++ii) {
    const Index i = static_cast<Index>(ii);
    auto sums = start(i);
    std::uint64_t count = 0;
    // Inlined into the scan (with TALUS_PAIR_INLINE terms): the terms of a pass become straight-line code.
    cells.for_each_neighbour(xa[i], xb, radius, [&](Index j, const Vec3& dx, double r2) __attribute__((always_inline)) {
      if (skip_self && j == i) return;
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
      detail::apply_terms(p, sums, terms...);
    });
    finish(i, sums);
    pairs += count;
  }
  return pairs;
}

}  // namespace talus::sph
