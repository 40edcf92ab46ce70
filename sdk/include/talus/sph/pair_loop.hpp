// The fused SPH pair loop (DESIGN.md, "Fast loops"): one neighbour traversal
// per pass, the per-pair quantities (dx, r, W, dW/dr) computed once and handed
// to every term of the pass. Terms are plain structs whose pair() inlines into
// the traversal: no virtual call, no allocation, no lookup by name.
//
// A pass is gather-style: particle i of set A sums over its neighbours j of
// set B (A and B may be the same set), so every particle writes only its own
// results: parallel over i without atomics, and deterministic whatever the
// thread count (DESIGN.md principle 8). A pass of one set against itself
// whose terms are symmetric in i and j can instead evaluate each pair once
// for both particles: sph/mutual_pass.hpp (the wcsph fluid-fluid force pass).
//
//   struct MySums { Vec3 v; double rho; Vec3 acc; };     // i-state and sums
//   auto start  = [&](Index i) { return MySums{vel[i], rho[i], {}}; };
//   auto finish = [&](Index i, const MySums& s) { acc[i] = s.acc; };
//   sph::pair_pass(n, pos, cells, kernel, sph::same_set, start, finish,
//                  sph::PressureForce{...}, sph::Continuity{...});
//
// A term is any type with `static constexpr bool uses_value, uses_gradient`
// and `template <class Sums> void pair(const sph::Pair&, Sums&) const`.
//
// A pass that also sums over particles (the force and torque on a body) is a
// reducing_pair_pass: finish(i, sums, acc) adds to a per-thread accumulator,
// and the partials are added in thread order, so the total is reproducible
// for a given thread count.
#pragma once

#include <cmath>
#include <cstdint>
#include <span>
#include <tuple>

#include <omp.h>

#include "talus/config.hpp"
#include "talus/kernel_table.hpp"
#include "talus/neighbour_grid.hpp"
#include "talus/sph/neighbour_records.hpp"
#include "talus/vec3.hpp"

namespace talus::sph {

// Neighbour j's fields as a pass that gathers them into its lanes hands them
// on (GatheredNeighbourFields, fluid_terms.hpp); other passes leave it empty
// and the terms read j's fields from the columns.
struct NeighbourState {
  Vec3 v;
  double rho = 0.0, p = 0.0, c = 0.0, inv_rho = 0.0;
};

// The per-pair quantities every term of a pass shares.
struct Pair {
  Index j = 0;       // neighbour index in set B
  Vec3 dx;           // x_i - x_j (minimum image on periodic axes)
  double r2 = 0.0;   // |dx|^2
  double r = 0.0;    // |dx|, filled when a term uses_value
  double w = 0.0;    // W(r), filled when a term uses_value
  double dw_r = 0.0; // (dW/dr)/r, filled when a term uses_gradient: grad_i W_ij = dx * dw_r
  double inv_r2e = 0.0;  // 1/(r^2 + pair_eta2(h)), filled with the gradient
  NeighbourState j_state;  // filled only by a pass that gathers j's fields
  Vec3 grad() const { return dx * dw_r; }
};

// eta^2 = (0.1 h)^2, the usual regularisation of the 1/r^2 in artificial
// viscosity and density diffusion (Monaghan 1992): Pair::inv_r2e.
inline double pair_eta2(double h) { return 0.01 * h * h; }

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

// Particle i's sums over its neighbours; returns the number of pairs.
template <class Sums, class... Terms>
TALUS_PAIR_INLINE std::uint64_t gather(Index i, const Vec3& xi, const NeighbourGrid& cells, const KernelTable& kernel,
                                       double radius, double eta2, bool skip_self, Sums& sums,
                                       const Terms&... terms) {
  constexpr bool need_value = (Terms::uses_value || ...);
  constexpr bool need_gradient = (Terms::uses_gradient || ...);
  static_assert(!(ReadsRecords<Terms> || ...), "a gather pass reads j's fields from the columns, not from records");
  std::uint64_t count = 0;
  // Inlined into the scan (with TALUS_PAIR_INLINE terms): the terms of a pass become straight-line code.
  cells.for_each_neighbour(xi, radius, [&](Index j, const Vec3& dx, double r2) __attribute__((always_inline)) {
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
    apply_terms(p, sums, terms...);
  });
  return count;
}
}  // namespace detail

// Runs the fused pass over particles i in [0, n) of set A (positions xa)
// against the neighbours in `cells` (built on the positions of set B).
// start(i) -> Sums, every term's pair(p, sums) per neighbour, finish(i, sums).
// Returns the number of pair evaluations (for throughput reports).
template <class Start, class Finish, class... Terms>
std::uint64_t pair_pass(std::size_t n, std::span<const Vec3> xa, const NeighbourGrid& cells, const KernelTable& kernel,
                        Sets sets, Start&& start, Finish&& finish, const Terms&... terms) {
  const double radius = kernel.support_radius();
  const double eta2 = pair_eta2(kernel.h());
  const bool skip_self = sets == Sets::same;
  std::uint64_t pairs = 0;
#pragma omp parallel for schedule(dynamic, 128) reduction(+ : pairs) if (n >= parallel_min)
  for (std::int64_t ii = 0; ii < static_cast<std::int64_t>(n); ++ii) {
    const Index i = static_cast<Index>(ii);
    auto sums = start(i);
    const std::uint64_t count = detail::gather(i, xa[i], cells, kernel, radius, eta2, skip_self, sums, terms...);
    finish(i, sums);
    pairs += count;
  }
  return pairs;
}

// A pair_pass that also reduces over particles: particles with skip(i) are
// left out before any neighbour search, finish(i, sums, acc) adds particle i's
// share to its thread's Acc (Acc{} is zero, `+=` adds), and the total is the
// thread partials added in thread order (static schedule: the same split, so
// the same sum, in every run at a given thread count). `pairs` gets the count.
template <class Acc, class Skip, class Start, class Finish, class... Terms>
Acc reducing_pair_pass(std::size_t n, std::span<const Vec3> xa, const NeighbourGrid& cells, const KernelTable& kernel,
                       Sets sets, std::uint64_t& pairs, Skip&& skip, Start&& start, Finish&& finish,
                       const Terms&... terms) {
  const double radius = kernel.support_radius();
  const double eta2 = pair_eta2(kernel.h());
  const bool skip_self = sets == Sets::same;
  Acc total{};
  std::uint64_t count = 0;
#pragma omp parallel reduction(+ : count)
  {
    Acc partial{};
#pragma omp for schedule(static)
    for (std::int64_t ii = 0; ii < static_cast<std::int64_t>(n); ++ii) {
      const Index i = static_cast<Index>(ii);
      if (skip(i)) continue;
      auto sums = start(i);
      count += detail::gather(i, xa[i], cells, kernel, radius, eta2, skip_self, sums, terms...);
      finish(i, sums, partial);
    }
#pragma omp for ordered schedule(static, 1)
    for (int t = 0; t < omp_get_num_threads(); ++t) {
#pragma omp ordered
      total += partial;
    }
  }
  pairs = count;
  return total;
}

// A term that wraps the terms of a pass on a body and also sums each pair's
// moment dx x (change of s.acc) into s.moment, so that non-central (viscous)
// pair forces give their exact torque: Sums carry `acc` and `moment`.
template <class... Terms>
struct WithPairMoment {
  static constexpr bool uses_value = (Terms::uses_value || ...);
  static constexpr bool uses_gradient = (Terms::uses_gradient || ...);
  std::tuple<Terms...> terms;
  template <class S>
  TALUS_PAIR_INLINE void pair(const Pair& q, S& s) const {
    const Vec3 before = s.acc;
    std::apply([&](const Terms&... t) { detail::apply_terms(q, s, t...); }, terms);
    s.moment += cross(q.dx, s.acc - before);
  }
};
template <class... Terms>
WithPairMoment<Terms...> with_pair_moment(const Terms&... terms) {
  return {{terms...}};
}

}  // namespace talus::sph
