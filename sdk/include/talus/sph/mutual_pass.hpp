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
// s is a LaneSums: i's state as the fluid terms read it (v, m, rho, inv_rho,
// p, c, mu, kh, mat) and the sums acc, drho, visc of that one pair.
//
// Terms whose neighbours are GatheredNeighbourFields (fluid_terms.hpp) read
// j's fields from records: each chunk of lanes gathers them (eight records at
// a time in float, four in double, with v from its column) before the terms
// run, and hands them on in Pair::j_state.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>

#include <omp.h>

#include "talus/config.hpp"
#include "talus/error.hpp"
#include "talus/kernel_table.hpp"
#include "talus/neighbour_grid.hpp"
#include "talus/sph/neighbour_records.hpp"
#include "talus/sph/pair_loop.hpp"
#include "talus/vec3.hpp"

namespace talus::sph {

// What one pair gives its later particle j.
struct PairReaction {
  Vec3 acc;
  double drho = 0.0;
};

// Per-particle accumulators of a force pass: acceleration and density rate,
// in double or (mixed precision) in float; what is added is in double.
template <class Real = double>
struct FluidReactions {
  VectorOf<Real>* acc = nullptr;
  Real* drho = nullptr;
  TALUS_PAIR_INLINE void add(Index k, const Vec3& a, double d) const {
    acc[k] = Vec3(acc[k]) + a;
    drho[k] += d;
  }
  void clear_one(Index k) const {
    acc[k] = Vec3{};
    drho[k] = 0;
  }
};

// What a mutual pass returns: its particle-neighbour evaluations (twice the
// pairs, as a gather pass would count them) and the largest
// |v_ij . x_ij|/(r^2 + eta^2) of any pair (the time-step bound; the same for
// i and j, so the largest over every particle's later pairs).
struct MutualPassResult {
  std::uint64_t evaluations = 0;
  double visc_max = 0.0;
};

// A chunk of particle i's pairs in lanes (structure of arrays): what the
// traversal found, stored there by the grid's scan, and the kernel's values.
struct PairLanes {
  static constexpr int size = NeighbourHits::size;
  NeighbourHits hits;  // j, dx, dy, dz, r2 and their count
  double r[size], w[size], dw_r[size], inv_r2e[size];
  GatheredLanes<size> gathered;  // j's fields, in a pass whose terms read them from records
};

// Keeps only the hits whose point is below `owned`, in their order.
inline void keep_owned(NeighbourHits& h, std::size_t owned) {
  int kept = 0;
  for (int k = 0; k < h.count; ++k)
    if (h.j[k] < owned) h.move(k, kept++);
  h.count = kept;
}

// The neighbour fields of the terms of a pass that read j's fields from
// records (the first such term's; every one of a pass has the same), or none.
inline std::nullptr_t records_of() { return nullptr; }
template <class Term, class... Rest>
auto records_of(const Term& term, const Rest&... rest) {
  if constexpr (ReadsRecords<Term>)
    return &term.nb;
  else
    return records_of(rest...);
}
template <class... Terms>
constexpr bool gathers_records = (ReadsRecords<Terms> || ...);

// j's fields into the lanes: from the records alone in float; in double
// v comes from its column.
template <class NB, int Size>
TALUS_PAIR_INLINE void gather_neighbours(const NB& nb, const Index* j, int n, GatheredLanes<Size>& out) {
  if constexpr (std::is_same_v<decltype(nb.record), const NeighbourRecord*>)
    gather_records(nb.record, j, n, out);
  else
    gather_records(nb.record, nb.velocity, j, n, out);
}

// Each lane's shares for i and for j: local to the evaluation, so the
// compiler can tell that the terms' reads of the particle fields never meet
// these stores.
struct LaneShares {
  double i_ax[PairLanes::size], i_ay[PairLanes::size], i_az[PairLanes::size], i_drho[PairLanes::size],
      i_visc[PairLanes::size];
  double j_ax[PairLanes::size], j_ay[PairLanes::size], j_az[PairLanes::size], j_drho[PairLanes::size];
};

// Particle i as the terms of one lane see it: its state by reference to a
// local copy (the same loads in every lane, hoisted out of the loop) and the
// sums of that lane's pair alone, so that the lanes share no accumulator.
// The members are those the fluid terms read (fluid_terms.hpp).
template <class S>
struct LaneSums {
  const Vec3& v;
  const double &m, &rho, &inv_rho, &p, &c, &mu, &kh;
  const std::int32_t& mat;
  Vec3 acc;
  double drho = 0.0, visc = 0.0;
  explicit LaneSums(const S& s)
      : v(s.v), m(s.m), rho(s.rho), inv_rho(s.inv_rho), p(s.p), c(s.c), mu(s.mu), kh(s.kh), mat(s.mat) {}
};

// Evaluates the lanes' pairs: the kernel's values, then every term's shares
// lane by lane (loops without calls or branches on the data, which the
// compiler vectorises), then i's shares summed and j's added to out, in lane
// order. Not inlined into the traversal: apart, each keeps its values in
// registers.
template <bool NeedValue, bool NeedGradient, class S, class Out, class... Terms>
[[gnu::noinline]] void run_lanes(PairLanes& L, const KernelTable& kernel, double eta2, S& sums, Out out,
                                 const Terms&... terms) {
  NeighbourHits& h = L.hits;
  const int n = h.count;
  constexpr bool gather = gathers_records<Terms...>;
  [[maybe_unused]] const auto gathered_from = records_of(terms...);  // nullptr when the terms read columns
  if constexpr (gather) {
    for (int k = n; k % 8 != 0; ++k) h.j[k] = h.j[0];  // whole eights: the spare lanes load a real record
    gather_neighbours(*gathered_from, h.j, n, L.gathered);
  }
  if constexpr (NeedValue)
    for (int k = 0; k < n; ++k) {
      L.r[k] = std::sqrt(h.r2[k]);
      L.w[k] = kernel.w(L.r[k]);
    }
  if constexpr (NeedGradient) {
    if (kernel.gradient_by_r2())
      kernel.dw_over_r_within_support(h.r2, L.dw_r, n);
    else
      for (int k = 0; k < n; ++k) L.dw_r[k] = kernel.dw_over_r_from_r2(h.r2[k]);
    for (int k = 0; k < n; ++k) L.inv_r2e[k] = 1.0 / (h.r2[k] + eta2);
  }
  LaneShares out_of;
  const S state = sums;  // a local copy: no store in the loop can alias it
  // The terms, lane by lane: the loop tests/sph/vectorised_pair_lanes.cmake checks.
  for (int k = 0; k < n; ++k) {
    Pair q;
    q.j = h.j[k];
    q.dx = Vec3{h.dx[k], h.dy[k], h.dz[k]};
    q.r2 = h.r2[k];
    if constexpr (NeedValue) {
      q.r = L.r[k];
      q.w = L.w[k];
    }
    if constexpr (NeedGradient) {
      q.dw_r = L.dw_r[k];
      q.inv_r2e = L.inv_r2e[k];
    }
    if constexpr (gather) {
      const GatheredLanes<PairLanes::size>& g = L.gathered;
      q.j_state = {Vec3{g.vx[k], g.vy[k], g.vz[k]}, g.rho[k], g.p[k], g.c[k], g.inv_rho[k]};
    }
    LaneSums<S> si(state);
    PairReaction rj;
    (terms.mutual(q, si, rj), ...);
    out_of.i_ax[k] = si.acc.x;
    out_of.i_ay[k] = si.acc.y;
    out_of.i_az[k] = si.acc.z;
    out_of.i_drho[k] = si.drho;
    out_of.i_visc[k] = si.visc;
    out_of.j_ax[k] = rj.acc.x;
    out_of.j_ay[k] = rj.acc.y;
    out_of.j_az[k] = rj.acc.z;
    out_of.j_drho[k] = rj.drho;
  }
  // i's shares summed in registers (sums itself lives in memory), j's added.
  const LaneShares& o = out_of;
  double ax = 0.0, ay = 0.0, az = 0.0, drho = 0.0, visc = sums.visc;
  for (int k = 0; k < n; ++k) {
    ax += o.i_ax[k];
    ay += o.i_ay[k];
    az += o.i_az[k];
    drho += o.i_drho[k];
    visc = std::max(visc, o.i_visc[k]);
    out.add(h.j[k], Vec3{o.j_ax[k], o.j_ay[k], o.j_az[k]}, o.j_drho[k]);
  }
  sums.acc += Vec3{ax, ay, az};
  sums.drho += drho;
  sums.visc = visc;
}

// Runs the mutual pass over every point binned in `cells` (set A = set B; a
// grid of one level whose radius() covers the kernel's support). start(i) ->
// Sums (with acc, drho, visc zero), every term's mutual() per pair, then out =
// the sum over pairs for every particle, and finish(i) once out holds
// particle i's total. Points from `owned` on are halo copies of another MPI
// rank's particles (talus/parallel.hpp): their totals are not wanted, so
// pairs of two of them are skipped, and only their pairs with owned points
// count (in the result's visc_max too).
template <class Real, class Start, class Finish, class... Terms>
MutualPassResult mutual_pair_pass(const NeighbourGrid& cells, const KernelTable& kernel, FluidReactions<Real> out,
                                  std::size_t owned, Start&& start, Finish&& finish, const Terms&... terms) {
  constexpr bool need_value = (Terms::uses_value || ...);
  constexpr bool need_gradient = (Terms::uses_gradient || ...);
  const std::span<const Index> order = cells.order();
  const std::size_t n = order.size();
  const double radius = kernel.support_radius();
  if (radius > cells.radius() || !cells.one_level())
    throw RunError("mutual pair pass: the neighbour grid must have one level whose radius covers the kernel's support");
  const double eta2 = pair_eta2(kernel.h());
  const int threads = n >= parallel_min ? omp_get_max_threads() : 1;
  std::uint64_t pairs = 0;
  double visc_max = 0.0;
  // Particle i's pairs with its later neighbours, a chunk of lanes at a
  // time as the grid stores them; returns the evaluations (twice the pairs).
  auto pairs_from = [&](std::size_t slot, PairLanes& lanes, double& visc) __attribute__((always_inline)) {
    const Index i = order[slot];
    auto sums = start(i);
    std::uint64_t count = 0;
    const bool halo_i = i >= owned;
    cells.later_neighbour_chunks(slot, radius, lanes.hits, [&](NeighbourHits& hits) {
      if (halo_i) keep_owned(hits, owned);  // pairs of two halo copies are not wanted
      count += static_cast<std::uint64_t>(hits.count);
      if (hits.count > 0) run_lanes<need_value, need_gradient>(lanes, kernel, eta2, sums, out, terms...);
    });
    out.add(i, sums.acc, sums.drho);
    visc = std::max(visc, sums.visc);
    return 2 * count;
  };
#pragma omp parallel num_threads(threads) reduction(+ : pairs) reduction(max : visc_max)
  {
    PairLanes lanes;
#pragma omp for schedule(static)
    for (std::int64_t k = 0; k < static_cast<std::int64_t>(n); ++k) out.clear_one(static_cast<Index>(k));
    for (int colour = 0; colour < cells.write_colours(); ++colour) {
      // Blocks hold very different numbers of particles (a free surface, a
      // collapsing column): dealt one at a time to whichever thread is free.
#pragma omp for schedule(dynamic, 1)
      for (std::int64_t b = 0; b < static_cast<std::int64_t>(cells.write_blocks(colour)); ++b)
        cells.for_each_write_block_run(colour, static_cast<std::size_t>(b), [&](std::size_t begin, std::size_t end) {
          for (std::size_t slot = begin; slot < end; ++slot) pairs += pairs_from(slot, lanes, visc_max);
        });
    }
#pragma omp for schedule(static)
    for (std::int64_t k = 0; k < static_cast<std::int64_t>(n); ++k) finish(static_cast<Index>(k));
  }
  return {pairs, visc_max};
}

}  // namespace talus::sph
