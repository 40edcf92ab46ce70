// The neighbour search of every particle method in Talus: the SPH pair
// passes and wall sets, the samplers of the writers, the host's cache
// re-sort and the depth-integrated run-out.
//
// Points are binned by a counting sort into cells of half the search radius
// and their coordinates copied, in cell order, into separate x, y, z arrays.
// A query visits, per row of cells (fixed y and z), only the x-range that can
// hold points within its reach and skips the rows that cannot, so it scans
// about 1.7 times the sphere's volume instead of the 6.4 times of a 3 x 3 x 3
// stencil of radius-sized cells (3D). Candidates are tested without a branch,
// and each hit's index, offset and squared distance are stored as the test
// forms them, a vector at a time, into a chunk of hits that is handed on
// when full: the scan never mispredicts, and a pass reads the chunk as its
// lanes without forming a distance twice. Blocks of 4^dim cells remember
// whether they hold a point, so that a query far from every point (a fluid
// particle in the middle of a tank, against the tank's wall particles) ends
// after a few byte reads.
//
// Search radii that differ by orders of magnitude (a thinning run-out front,
// where the smoothing length grows while the bulk keeps the scene's) are
// binned into levels: level k holds radii in (R 2^(k-1), R 2^k], level 0
// those up to R, each level on its own cells of half its bound. A query's
// cost is then set by the local radii, not by a handful of large ones.
//
// Along a periodic axis the cell range of a query is taken unwrapped, so
// every image of a point within reach is reported, once, even for a reach
// longer than the period.
//
// A grid of one level holds cell starts only for the planes of cells along
// z (the outermost axis of the sorted order) that its points occupy, so its
// memory follows the points (the fluid in the lower part of a tall domain,
// a tank's walls), not the domain; the cells and the order are the same.
//
// Query contract: f(j, dx, r2) for every binned point j and image with
// r2 = |dx|^2 < reach^2, dx = x - x_j (the image's offset), the point itself
// included if it was binned; or the same hits a chunk (NeighbourHits) at a
// time. Nothing allocates after the first build at a given size and number
// of levels.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <span>
#include <string>
#include <vector>

#if defined(__AVX512F__) && defined(__AVX512VL__)
#include <immintrin.h>
#endif

#include "talus/config.hpp"
#include "talus/error.hpp"
#include "talus/vec3.hpp"

namespace talus {

// Cells of at least `cell` along an axis of `length`: floor(length / cell),
// at least 1, and capped so that the conversion to int stays defined (a
// coarser binning than asked is still correct, only slower).
inline int cells_along(double length, double cell) {
  const double n = std::floor(length / cell);
  constexpr double most = 1 << 24;
  return n >= 1.0 ? static_cast<int>(std::min(n, most)) : 1;
}

// Halves the axis with the most cells until the grid has at most 2^24 cells.
// Points far apart, such as a wall spaced 1e19 m, ask for more cells than a
// size_t counts; coarser cells than asked are still correct, only slower.
inline void fit_cells(std::array<int, 3>& n) {
  constexpr double most = 1 << 24;
  while (static_cast<double>(n[0]) * n[1] * n[2] > most) {
    int a = 0;
    for (int b = 1; b < 3; ++b)
      if (n[b] > n[a]) a = b;
    n[a] = std::max(n[a] / 2, 1);
  }
}

// floor(s) as an int within [lo, hi]; clamped before the conversion, which
// is undefined for what an int cannot hold (a point far outside the grid).
// NaN gives lo.
inline int floor_within(double s, int lo, int hi) {
  const double k = std::floor(s);
  return k > lo ? (k < hi ? static_cast<int>(k) : hi) : lo;
}

// Hits of one query in the order the scan found them, as structure of
// arrays: point j, dx = x - x_j (the image's offset) and r2 = |dx|^2. The
// scan stores a whole vector of hits at a time, so the arrays have room for
// one vector beyond the `size` hits a full chunk holds.
struct NeighbourHits {
  static constexpr int size = 64;   // hits of a full chunk
  static constexpr int vector = 8;  // the most hits one test adds
  int count = 0;
  Index j[size + vector];
  double dx[size + vector], dy[size + vector], dz[size + vector], r2[size + vector];
  // Hit `from` into slot `to` (compacting or carrying hits to the front).
  void move(int from, int to) {
    j[to] = j[from];
    dx[to] = dx[from];
    dy[to] = dy[from];
    dz[to] = dz[from];
    r2[to] = r2[from];
  }
};

class NeighbourGrid {
 public:
  static constexpr int max_levels = 24;

  // lo/hi bound the points (points outside are kept in the edge cells, which
  // stays correct, only slower); along a periodic axis they are the period.
  // `radius` is the largest search radius of level 0: with build(pos), of
  // every query.
  void configure(int dim, Vec3 lo, Vec3 hi, double radius, std::array<bool, 3> periodic = {}) {
    dim_ = dim;
    lo_ = lo;
    radius_ = radius;
    periodic_ = {};
    length_ = {0.0, 0.0, 0.0};
    for (int a = 0; a < dim && a < 3; ++a) {
      periodic_[a] = periodic[a];
      length_[a] = hi[a] - lo[a];
    }
    any_periodic_ = periodic_[0] || periodic_[1] || periodic_[2];
    lay_out_levels(1);
  }

  // Bins points that are all searched with at most radius().
  void build(std::span<const Vec3> pos) {
    const std::size_t n = pos.size();
    std::fill(level_max_.begin(), level_max_.end(), 0.0);
    if (n > 0) level_max_[0] = radius_;
    reserve_keys(n);
    const Level& L = level_[0];
    Index low = std::numeric_limits<Index>::max(), high = 0;
#pragma omp parallel for schedule(static) reduction(min : low) reduction(max : high) if (n > 4096)
    for (std::size_t i = 0; i < n; ++i) {
      const auto k = static_cast<Index>(L.cell_index(pos[i], lo_, dim_));
      set_key(i, k);
      low = std::min(low, k);
      high = std::max(high, k);
    }
    sort_into_cells(pos, hold_planes(low, high, n));
  }

  // Bins only the listed points pos[rows[q]] (one body's rows of a store
  // that holds several), reported by their index in pos.
  void build(std::span<const Vec3> pos, std::span<const Index> rows) {
    const std::size_t n = rows.size();
    std::fill(level_max_.begin(), level_max_.end(), 0.0);
    if (n > 0) level_max_[0] = radius_;
    reserve_keys(n);
    const Level& L = level_[0];
    Index low = std::numeric_limits<Index>::max(), high = 0;
    for (std::size_t q = 0; q < n; ++q) {
      const auto k = static_cast<Index>(L.cell_index(pos[rows[q]], lo_, dim_));
      set_key(q, k);
      low = std::min(low, k);
      high = std::max(high, k);
    }
    sort_into_cells(n, [&](std::size_t q) { return rows[q]; }, pos, hold_planes(low, high, n));
  }

  // Bins points with their own search radii, each into the level of its radius.
  void build(std::span<const Vec3> pos, std::span<const double> radius) {
    const std::size_t n = pos.size();
    int top = 0;
    for (std::size_t i = 0; i < n; ++i) top = std::max(top, level_of(radius[i]));
    if (top >= static_cast<int>(level_.size())) lay_out_levels(top + 1);
    std::fill(level_max_.begin(), level_max_.end(), 0.0);
    reserve_keys(n);
    for (std::size_t i = 0; i < n; ++i) {
      const int k = level_of(radius[i]);
      level_max_[k] = std::max(level_max_[k], radius[i]);
      set_key(i, static_cast<Index>(level_[k].offset + level_[k].cell_index(pos[i], lo_, dim_)));
    }
    hold_all_planes();
    sort_into_cells(pos, 0);
  }

  // The binned points' indices in cell order (level by level).
  std::span<const Index> order() const { return order_; }
  double radius() const { return radius_; }
  double largest_radius() const { return *std::max_element(level_max_.begin(), level_max_.end()); }

  // Every point j within `reach` of x (a gather: reach is the caller's radius).
  template <class F>
  TALUS_PAIR_INLINE void for_each_neighbour(const Vec3& x, double reach, F&& f) const {
    NeighbourHits hits;
    neighbour_chunks(x, reach, hits, [&](const NeighbourHits& h) { each_hit(h, f); });
  }

  // The same hits a chunk at a time: chunk(hits) with `size` hits while more
  // follow, then once with the rest, if any. `hits` is the caller's (a pass
  // keeps its lanes there) and holds none before and after.
  template <class Chunk>
  TALUS_PAIR_INLINE void neighbour_chunks(const Vec3& x, double reach, NeighbourHits& hits, Chunk&& chunk) const {
    if (any_periodic_)
      query<true, false>(x, reach, hits, chunk);
    else
      query<false, false>(x, reach, hits, chunk);
  }

  // Every point j within `reach` of the binned point in sorted slot `slot`
  // whose own slot comes later: each pair of binned points (and each image of
  // one on a periodic axis) is reported from exactly one side, its earlier
  // slot, for a pass that evaluates a pair once for both particles.
  // dx = x_slot - x_j as in for_each_neighbour.
  template <class F>
  TALUS_PAIR_INLINE void for_each_later_neighbour(std::size_t slot, double reach, F&& f) const {
    NeighbourHits hits;
    later_neighbour_chunks(slot, reach, hits, [&](const NeighbourHits& h) { each_hit(h, f); });
  }

  // The same hits a chunk at a time, as neighbour_chunks hands them on.
  template <class Chunk>
  TALUS_PAIR_INLINE void later_neighbour_chunks(std::size_t slot, double reach, NeighbourHits& hits,
                                                Chunk&& chunk) const {
    const Vec3 x{xs_[slot], ys_[slot], zs_[slot]};
    const Index first = static_cast<Index>(slot + 1);
    if (any_periodic_)
      query<true, false>(x, reach, hits, chunk, first);
    else
      query<false, false>(x, reach, hits, chunk, first);
  }

  // Write blocks, for a pass that adds each pair's share to both of its
  // points from several threads with no copy of the output per thread (a grid
  // of one level, searched within radius()). The cells are grouped, along the
  // outer axes of the sorted order (z and y in 3D, y in 2D), into blocks at
  // least two cells (one search radius) wide, whole along x; runs of a block
  // are then whole rows of cells, which keeps the order of the scan close to
  // the sorted order, and two threads seldom write to one cache line. A
  // point's later neighbours lie in its own block or the blocks next to it,
  // and along the outermost closed axis only in its own or the next one
  // (later slots are not lower there). Blocks of one colour are three
  // blocks apart (two along that axis) and share no neighbour: a colour's
  // blocks can run at once, and the colours run one after the other. Every
  // point then receives its shares in an order that the cells alone fix, so
  // the result is the same on any number of threads.
  int write_colours() const { return write_step_[0] * write_step_[1]; }

  // Whether every binned point is on level 0 (the write blocks cover only it).
  bool one_level() const {
    return std::all_of(level_max_.begin() + 1, level_max_.end(), [](double r) { return !(r > 0.0); });
  }

  // The number of blocks of a colour.
  std::size_t write_blocks(int colour) const {
    return static_cast<std::size_t>(blocks_of_colour(colour % write_step_[0], 0)) *
           blocks_of_colour(colour / write_step_[0], 1);
  }

  // f(begin, end) for the runs of sorted slots of block k of a colour, in
  // slot order.
  template <class F>
  void for_each_write_block_run(int colour, std::size_t k, F&& f) const {
    const Level& L = level_[0];
    const int first[2] = {colour % write_step_[0], colour / write_step_[0]};
    const int along = blocks_of_colour(first[0], 0);
    const int block[2] = {first[0] + write_step_[0] * static_cast<int>(k % along),
                          first[1] + write_step_[1] * static_cast<int>(k / along)};
    std::array<int, 3> lo{0, 0, 0}, hi = L.n;
    for (int b = 0; b < 2; ++b) {
      const int a = write_axis_[b];
      const long long n = L.n[a], count = write_blocks_along_[b];
      lo[a] = static_cast<int>(block[b] * n / count);
      hi[a] = static_cast<int>((block[b] + 1) * n / count);
    }
    Index begin = 0, end = 0;
    for (int cz = lo[2]; cz < hi[2]; ++cz) {
      if (!L.holds_plane(cz)) continue;  // no point there
      for (int cy = lo[1]; cy < hi[1]; ++cy) {
        const std::size_t row = L.row_index(cz, cy);
        const Index s0 = cell_start_[row + lo[0]], s1 = cell_start_[row + hi[0]];
        if (s0 == s1) continue;
        if (s0 != end) {
          if (end > begin) f(std::size_t{begin}, std::size_t{end});
          begin = s0;
        }
        end = s1;
      }
    }
    if (end > begin) f(std::size_t{begin}, std::size_t{end});
  }

  // Every point j of a level within max(own, the level's largest radius) of x:
  // a superset of the pairs with r < max(R_x, R_j), which the caller keeps.
  template <class F>
  void for_each_candidate_pair(const Vec3& x, double own, F&& f) const {
    NeighbourHits hits;
    auto chunk = [&](const NeighbourHits& h) { each_hit(h, f); };
    if (any_periodic_)
      query<true, true>(x, own, hits, chunk);
    else
      query<false, true>(x, own, hits, chunk);
  }

 private:
  struct Level {
    std::array<int, 3> n{1, 1, 1};
    std::array<double, 3> cell{1, 1, 1}, inv{1, 1, 1};
    std::size_t offset = 0;  // first cell in cell_start_
    std::array<int, 3> blocks{1, 1, 1};  // blocks of block_cells^dim cells per axis
    std::size_t block_offset = 0;        // first block in block_filled_
    // The planes of cells along z that cell_start_ holds: [z_first, z_first + z_planes).
    int z_first = 0, z_planes = 0;
    std::size_t plane_cells() const { return static_cast<std::size_t>(n[0]) * n[1]; }
    bool holds_plane(int z) const { return z >= z_first && z < z_first + z_planes; }
    // Where the cells of row y of held plane z start in cell_start_.
    std::size_t row_index(int z, int y) const {
      return offset + (static_cast<std::size_t>(z - z_first) * n[1] + y) * n[0];
    }
    std::size_t block_index(int bx, int by, int bz) const {
      return block_offset + (static_cast<std::size_t>(bz) * blocks[1] + by) * blocks[0] + bx;
    }
    int axis_cell(double v, double lo, int a) const { return floor_within((v - lo) * inv[a], 0, n[a] - 1); }
    std::size_t cell_index(const Vec3& p, const Vec3& lo, int dim) const {
      const int z = dim == 3 ? axis_cell(p.z, lo.z, 2) : 0;
      return (static_cast<std::size_t>(z) * n[1] + axis_cell(p.y, lo.y, 1)) * n[0] + axis_cell(p.x, lo.x, 0);
    }
  };

  // Blocks of the colours that start at block c along block axis b.
  int blocks_of_colour(int c, int b) const {
    return std::max(0, (write_blocks_along_[b] - c + write_step_[b] - 1) / write_step_[b]);
  }

  // The write blocks of level 0, half as many as cells along each divided
  // axis (z and y in 3D, y in 2D). Along a periodic axis the first and last
  // blocks are neighbours (either can write to the other): more than three
  // blocks must come in a multiple of three, and the colours repeat every
  // three blocks.
  void lay_out_write_blocks() {
    const Level& L = level_[0];
    const int outer = std::clamp(dim_, 1, 3) - 1;
    for (int b = 0; b < 2; ++b) {
      const int a = outer - b;
      if (a < 1) {  // x is never divided: a block's runs stay whole rows
        write_axis_[b] = 0;
        write_blocks_along_[b] = 1;
        write_step_[b] = 1;
        continue;
      }
      write_axis_[b] = a;
      int count = std::max(L.n[a] / 2, 1);
      if (periodic_[a] && count > 3) count -= count % 3;
      write_blocks_along_[b] = count;
      write_step_[b] = b == 0 && !periodic_[a] ? 2 : 3;
    }
  }

  int level_of(double r) const {
    if (!(r > radius_)) return 0;
    const int k = static_cast<int>(std::ceil(std::log2(r / radius_) - 1e-12));
    if (!(k < max_levels)) {
      char text[160];
      std::snprintf(text, sizeof text,
                    "neighbour search: a search radius of %.4g m exceeds 2^%d times the scene's (%.4g m)", r,
                    max_levels, radius_);
      throw RunError(text);
    }
    return std::max(k, 0);
  }

  void lay_out_levels(int count) {
    level_.resize(count);
    level_max_.assign(count, 0.0);
    std::size_t total = 0, block_total = 0;
    for (int k = 0; k < count; ++k) {
      Level& L = level_[k];
      const double cell = 0.5 * radius_ * std::ldexp(1.0, k);
      L.n = {1, 1, 1};
      for (int a = 0; a < dim_ && a < 3; ++a) L.n[a] = cells_along(length_[a], cell);
      fit_cells(L.n);
      for (int a = 0; a < dim_ && a < 3; ++a) {
        L.cell[a] = length_[a] / L.n[a];
        L.inv[a] = 1.0 / L.cell[a];
      }
      L.offset = total;
      L.z_first = 0;
      L.z_planes = 0;  // until a build
      total += static_cast<std::size_t>(L.n[0]) * L.n[1] * L.n[2];
      for (int a = 0; a < 3; ++a) L.blocks[a] = (L.n[a] + block_cells - 1) / block_cells;
      L.block_offset = block_total;
      block_total += static_cast<std::size_t>(L.blocks[0]) * L.blocks[1] * L.blocks[2];
    }
    // Room for every plane, written only where a build holds planes.
    cell_start_.assign(1, 0);
    cell_start_.reserve(total + 1);
    total_cells_ = total;
    block_filled_.assign(block_total, 0);
    lay_out_write_blocks();
  }

  // Level 0 holds the planes from that of key `low` to that of key `high`
  // (the points' least and greatest; one plane without points), the other
  // levels none. Returns the key of the first cell held.
  Index hold_planes(Index low, Index high, std::size_t n) {
    Level& L = level_[0];
    const std::size_t plane = L.plane_cells();
    L.z_first = n > 0 ? static_cast<int>(low / plane) : 0;
    L.z_planes = n > 0 ? static_cast<int>(high / plane) - L.z_first + 1 : 1;
    for (std::size_t k = 1; k < level_.size(); ++k) level_[k].z_planes = 0;
    cell_start_.resize(plane * L.z_planes + 1);
    return static_cast<Index>(L.z_first * plane);
  }

  // Every level holds every plane (the levels' offsets lie them end to end).
  void hold_all_planes() {
    for (Level& L : level_) {
      L.z_first = 0;
      L.z_planes = L.n[2];
    }
    cell_start_.resize(total_cells_ + 1);
  }

  // Which blocks of cells hold a point: a query whose reach meets only empty
  // blocks (a fluid particle far from every wall particle) returns at once.
  void mark_filled_blocks() {
    std::fill(block_filled_.begin(), block_filled_.end(), 0);
    for (const Level& L : level_)
      for (int cz = L.z_first; cz < L.z_first + L.z_planes; ++cz)
        for (int cy = 0; cy < L.n[1]; ++cy) {
          const std::size_t row = L.row_index(cz, cy);
          for (int cx = 0; cx < L.n[0]; ++cx)
            if (cell_start_[row + cx + 1] > cell_start_[row + cx])
              block_filled_[L.block_index(cx / block_cells, cy / block_cells, cz / block_cells)] = 1;
        }
  }

  // Whether any block within the cell ranges of a query holds a point (closed axes only).
  bool any_filled_block(const Level& L, const int (&first)[3], const int (&last)[3]) const {
    for (int bz = first[2] / block_cells; bz <= last[2] / block_cells; ++bz)
      for (int by = first[1] / block_cells; by <= last[1] / block_cells; ++by)
        for (int bx = first[0] / block_cells; bx <= last[0] / block_cells; ++bx)
          if (block_filled_[L.block_index(bx, by, bz)]) return true;
    return false;
  }

  // The points' cell keys live in zs_'s bytes until the sort has read them
  // (an array of their own would cost 4 bytes a point for the grid's life).
  static_assert(sizeof(Index) <= sizeof(double), "a key must fit in a coordinate's bytes");
  void reserve_keys(std::size_t n) { zs_.resize(n); }
  void set_key(std::size_t i, Index key) {
    std::memcpy(reinterpret_cast<char*>(zs_.data()) + i * sizeof key, &key, sizeof key);
  }
  Index key(std::size_t i) const {
    Index k;
    std::memcpy(&k, reinterpret_cast<const char*>(zs_.data()) + i * sizeof k, sizeof k);
    return k;
  }

  // Counting sort of the keys into order_, with the coordinates copied
  // alongside; key k counts in cell_start_[k - first] (the first held cell).
  void sort_into_cells(std::span<const Vec3> pos, Index first) {
    sort_into_cells(pos.size(), [](std::size_t i) { return static_cast<Index>(i); }, pos, first);
  }
  // The same for n binned points whose q-th is pos[point(q)].
  template <class Point>
  void sort_into_cells(std::size_t n, Point point, std::span<const Vec3> pos, Index first) {
    order_.resize(n);
    xs_.resize(n);
    ys_.resize(n);
    std::fill(cell_start_.begin(), cell_start_.end(), 0);
    for (std::size_t i = 0; i < n; ++i) ++cell_start_[key(i) - first + 1];
    for (std::size_t c = 1; c < cell_start_.size(); ++c) cell_start_[c] += cell_start_[c - 1];
    // Each cell's start is its cursor while filling: it ends as the next cell's start, and the
    // starts are shifted back by one afterwards (no second array of cells).
    for (std::size_t i = 0; i < n; ++i) {
      const Index s = cell_start_[key(i) - first]++;
      const Index j = point(i);
      order_[s] = j;
      xs_[s] = pos[j].x;
      ys_[s] = pos[j].y;
    }
    // z last, over the keys' bytes, once the last key has been read.
    const bool planar = dim_ != 3;
#pragma omp parallel for schedule(static) if (n > 4096)
    for (std::size_t s = 0; s < n; ++s) zs_[s] = planar ? 0.0 : pos[order_[s]].z;
    std::copy_backward(cell_start_.begin(), cell_start_.end() - 2, cell_start_.end() - 1);
    cell_start_[0] = 0;
    if (!any_periodic_) mark_filled_blocks();
  }

  static constexpr int block_cells = 4;  // cells per block edge (two search radii)

  template <class F>
  static void each_hit(const NeighbourHits& h, F& f) {
    for (int k = 0; k < h.count; ++k) f(h.j[k], Vec3{h.dx[k], h.dy[k], h.dz[k]}, h.r2[k]);
  }

  // Hands on the first min(count, size) of the `count` hits stored, and moves
  // the rest to the front; returns how many moved. Out of line: it runs once
  // a chunk, and a pass's chunk is compiled once instead of at every scan.
  template <class Chunk>
  [[gnu::noinline]] static int hand_on(NeighbourHits& h, int count, Chunk& chunk) {
    const int full = std::min(count, NeighbourHits::size);
    h.count = full;
    chunk(h);
    const int rest = count - full;
    for (int k = 0; k < rest; ++k) h.move(full + k, k);
    h.count = rest;
    return rest;
  }

  // Only slots from `first` on are scanned (a later-neighbour query).
  template <bool Periodic, bool Candidates, class Chunk>
  TALUS_PAIR_INLINE void query(const Vec3& at, double own, NeighbourHits& hits, Chunk& chunk, Index first = 0) const {
    const Vec3 x{at.x, at.y, dim_ == 3 ? at.z : 0.0};
    for (std::size_t k = 0; k < level_.size(); ++k) {
      if (!(level_max_[k] > 0.0)) continue;  // an empty level
      const double reach = Candidates ? std::max(own, level_max_[k]) : own;
      query_level<Periodic>(level_[k], x, reach, first, hits, chunk);
    }
    if (hits.count > 0) hand_on(hits, hits.count, chunk);
  }

  // The cells of level L within `reach` of x along each axis, row by row.
  // A row whose cells all lie beyond `reach` across it (one in seven of a
  // query's rows, on cells of half the reach) is skipped for a few flops;
  // every other row is scanned over the same cells along x: narrowing each
  // to its chord of the sphere would cost more (a root and floors a row)
  // than the distance tests of the candidates it would save.
  template <bool Periodic, class Chunk>
  TALUS_PAIR_INLINE void query_level(const Level& L, const Vec3& x, double reach, Index first, NeighbourHits& hits,
                                     Chunk& chunk) const {
    int lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    for (int a = 0; a < dim_ && a < 3; ++a) cell_range(L, x[a], reach, a, lo[a], hi[a]);
    // A point binned here (a later-neighbour query) always finds its own block filled.
    if constexpr (!Periodic)
      if (first == 0 && !any_filled_block(L, lo, hi)) return;
    const double r2max = reach * reach;
    const double ty = (x.y - lo_.y) * L.inv[1], tz = (x.z - lo_.z) * L.inv[2];
    const int x0 = lo[0], x1 = hi[0], y0 = lo[1], y1 = hi[1], z0 = lo[2], z1 = hi[2];
    for (int cz = z0; cz <= z1; ++cz) {
      int iz = 0;
      const int rz = wrap(L, cz, 2, iz);
      if (!L.holds_plane(rz)) continue;  // no point there
      const std::size_t plane = L.row_index(rz, 0);
      // A later-neighbour query skips the rows that end before `first` (about half of them).
      if (cell_start_[plane + L.plane_cells()] <= first) continue;
      const double gz = gap_to_cell(L, 2, cz, tz);
      for (int cy = y0; cy <= y1; ++cy) {
        int iy = 0;
        const int ry = wrap(L, cy, 1, iy);
        const std::size_t row = plane + static_cast<std::size_t>(ry) * L.n[0];
        if (cell_start_[row + L.n[0]] <= first) continue;
        const double gy = gap_to_cell(L, 1, cy, ty);
        if (gy * gy + gz * gz >= r2max) continue;  // no point of the row within reach
        if (!periodic_[0]) {
          const Vec3 q = Periodic ? x - image_shift(0, iy, iz) : x;
          scan(row + x0, row + x1 + 1, q, r2max, first, hits, chunk);
        } else {
          for (int cx = x0; cx <= x1; ++cx) {
            int ix = 0;
            const int rx = wrap(L, cx, 0, ix);
            scan(row + rx, row + rx + 1, x - image_shift(ix, iy, iz), r2max, first, hits, chunk);
          }
        }
      }
    }
  }

  // The cells [v - reach, v + reach] overlaps along axis a: unwrapped on a
  // periodic axis, within the grid on a closed one (whose edge cells hold
  // the points beyond it).
  void cell_range(const Level& L, double v, double reach, int a, int& first, int& last) const {
    constexpr int far = 1 << 28;  // images this far never matter; keeps the ints defined
    const int lo = periodic_[a] ? -far : 0, hi = periodic_[a] ? far : L.n[a] - 1;
    first = floor_within((v - reach - lo_[a]) * L.inv[a], lo, hi);
    last = floor_within((v + reach - lo_[a]) * L.inv[a], lo, hi);
  }

  // A lower bound on |v - w| for every w binned in the unwrapped cell k of
  // axis a, t = (v - lo)/cell: the distance from v to the cell's extent less
  // a margin far above rounding, and 0 towards the outside of a closed axis,
  // whose edge cells also hold the points beyond the grid.
  double gap_to_cell(const Level& L, int a, int k, double t) const {
    const bool closed = !periodic_[a];
    const double below = closed && k == 0 ? 0.0 : k - t;                    // v below the cell
    const double above = closed && k == L.n[a] - 1 ? 0.0 : t - (k + 1.0);  // v above it
    return std::max(0.0, std::max(below, above) - 1e-9) * L.cell[a];
  }

  // The stored cell of an unwrapped cell coordinate k, and its image (k = stored + image n).
  static int wrap(const Level& L, int k, int a, int& image) {
    if (k >= 0 && k < L.n[a]) return k;
    image = static_cast<int>(std::floor(static_cast<double>(k) / L.n[a]));
    return k - image * L.n[a];
  }

  // Where image (ix, iy, iz) of the stored points lies: a query at x meets
  // them as a query at x minus this shift meets the stored points.
  Vec3 image_shift(int ix, int iy, int iz) const {
    return Vec3{ix * length_[0], iy * length_[1], iz * length_[2]};
  }

  // |dx|^2 as the vector scan forms it: in the order GCC contracts
  // dx*dx + dy*dy + dz*dz into, so that a pass that formed the distance
  // itself would find the same bits. Fused only where the target has FMA:
  // elsewhere std::fma would be a library call per candidate (and there is
  // no vector scan to agree with).
  static double distance2(double dx, double dy, double dz) {
#if defined(__FMA__)
    return std::fma(dz, dz, std::fma(dx, dx, dy * dy));
#else
    return dx * dx + dy * dy + dz * dz;
#endif
  }

  // Tests the sorted points of cells [c0, c1) from slot `first` on against
  // the query point q without a branch on the outcome, and stores the hits
  // into the chunk, handing it on when full. With AVX-512, eight points a
  // test (the last test of a run masked to the points left) and the hits
  // compressed into place; otherwise one by one with the same operations in
  // the same order, so a point's outcome is the same on either path.
  template <class Chunk>
  TALUS_PAIR_INLINE void scan(std::size_t c0, std::size_t c1, const Vec3& q, double r2max, Index first,
                              NeighbourHits& hits, Chunk& chunk) const {
    const Index e = cell_start_[c1];
    // In registers: the stores into the chunk may alias anything, so members would be reloaded per test.
    const double *xs = xs_.data(), *ys = ys_.data(), *zs = zs_.data();
    const Index* order = order_.data();
    int count = hits.count;
    Index s = std::max(cell_start_[c0], first);
#if defined(__AVX512F__) && defined(__AVX512VL__)
    static_assert(NeighbourHits::vector == 8 && sizeof(Index) == 4);
    const __m512d vx = _mm512_set1_pd(q.x), vy = _mm512_set1_pd(q.y), vz = _mm512_set1_pd(q.z),
                  vmax = _mm512_set1_pd(r2max);
    for (; s < e; s += NeighbourHits::vector) {
      const Index left = e - s;
      const __mmask8 live = left >= 8 ? __mmask8(0xFF) : static_cast<__mmask8>((1u << left) - 1u);
      const __m512d dx = _mm512_sub_pd(vx, _mm512_maskz_loadu_pd(live, xs + s));
      const __m512d dy = _mm512_sub_pd(vy, _mm512_maskz_loadu_pd(live, ys + s));
      const __m512d dz = _mm512_sub_pd(vz, _mm512_maskz_loadu_pd(live, zs + s));
      const __m512d r2 = _mm512_fmadd_pd(dz, dz, _mm512_fmadd_pd(dx, dx, _mm512_mul_pd(dy, dy)));
      const __mmask8 within = _mm512_mask_cmp_pd_mask(live, r2, vmax, _CMP_LT_OQ);
      const __m256i j = _mm256_maskz_loadu_epi32(live, order + s);
      _mm256_storeu_si256(reinterpret_cast<__m256i*>(hits.j + count), _mm256_maskz_compress_epi32(within, j));
      _mm512_storeu_pd(hits.dx + count, _mm512_maskz_compress_pd(within, dx));
      _mm512_storeu_pd(hits.dy + count, _mm512_maskz_compress_pd(within, dy));
      _mm512_storeu_pd(hits.dz + count, _mm512_maskz_compress_pd(within, dz));
      _mm512_storeu_pd(hits.r2 + count, _mm512_maskz_compress_pd(within, r2));
      count += __builtin_popcount(within);
      if (count >= NeighbourHits::size) count = hand_on(hits, count, chunk);
    }
#else
    for (; s < e; ++s) {
      const double dx = q.x - xs[s], dy = q.y - ys[s], dz = q.z - zs[s];
      const double r2 = distance2(dx, dy, dz);
      hits.j[count] = order[s];
      hits.dx[count] = dx;
      hits.dy[count] = dy;
      hits.dz[count] = dz;
      hits.r2[count] = r2;
      count += r2 < r2max ? 1 : 0;
      if (count >= NeighbourHits::size) count = hand_on(hits, count, chunk);
    }
#endif
    hits.count = count;
  }

  int dim_ = 3;
  Vec3 lo_{};
  std::array<double, 3> length_{0, 0, 0};
  double radius_ = 0.0;
  std::array<bool, 3> periodic_{};
  bool any_periodic_ = false;
  std::vector<Level> level_;
  std::vector<double> level_max_;  // largest search radius binned per level; 0: empty
  std::vector<Index> cell_start_, order_;  // cell_start_: the held planes' cells, then their end
  std::size_t total_cells_ = 0;              // every level's cells
  std::vector<std::uint8_t> block_filled_;  // per block of cells: 1 if it holds a point
  std::vector<double> xs_, ys_, zs_;  // the points' coordinates in order_ (zs_: their keys while sorting)
  std::array<int, 2> write_axis_{2, 1};          // the axes the write blocks divide, outermost first
  std::array<int, 2> write_blocks_along_{1, 1};  // blocks along each
  std::array<int, 2> write_step_{2, 3};          // blocks between two of one colour along each
};

}  // namespace talus
