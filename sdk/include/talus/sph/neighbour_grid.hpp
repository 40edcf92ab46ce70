// The neighbour search of the SPH pair passes: a cell grid of half the search
// radius whose positions are copied, at build, into cell order as separate
// x, y, z arrays. A query visits, per row of cells (fixed y and z), only the
// x-range that can hold points within the radius, rows that cannot are
// skipped, so it scans about 1.7 times the sphere's volume instead of the 6.4
// times of a 3 x 3 x 3 stencil of radius-sized cells (3D). Candidates are
// tested without a branch and the hits handed to the caller in chunks, so the
// scan never mispredicts on the in/out test.
//
// Same query contract as talus::CellList: f(j, dx, r2) for every point j with
// |x - x_j| < radius, dx = x - x_j (minimum image on periodic axes), the
// point itself included if it was built in. Nothing allocates after the first
// build at a given size.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "talus/cell_list.hpp"  // cells_along, short_number
#include "talus/config.hpp"
#include "talus/error.hpp"
#include "talus/vec3.hpp"

namespace talus::sph {

class NeighbourGrid {
 public:
  // lo/hi bound the points (points outside are clamped into the edge cells,
  // which stays correct, only slower); along periodic axes they are the period.
  void configure(int dim, Vec3 lo, Vec3 hi, double radius, std::array<bool, 3> periodic = {}) {
    dim_ = dim;
    lo_ = lo;
    radius_ = radius;
    periodic_ = periodic;
    for (int a = 0; a < 3; ++a) {
      if (a >= dim) {
        n_[a] = 1;
        cell_[a] = 1.0;
        period_[a] = 0.0;
        continue;
      }
      const double length = hi[a] - lo[a];
      n_[a] = cells_along(2.0 * length, radius);
      if (periodic[a] && n_[a] < 5)
        throw InputError("error: neighbour search: the periodic axis " + std::string(1, static_cast<char>('x' + a)) +
                         " spans " + short_number(length) + " m, less than 2.5 search radii (2.5 x " +
                         short_number(radius) + " m)");
    }
    fit_cells(n_, 5);
    for (int a = 0; a < dim && a < 3; ++a) {
      cell_[a] = (hi[a] - lo[a]) / n_[a];
      period_[a] = periodic[a] ? hi[a] - lo[a] : 0.0;
    }
    inv_cell_ = {1.0 / cell_[0], 1.0 / cell_[1], 1.0 / cell_[2]};
    cell_start_.assign(static_cast<std::size_t>(n_[0]) * n_[1] * n_[2] + 1, 0);
  }

  void build(std::span<const Vec3> pos) {
    const std::size_t n = pos.size();
    cell_of_.resize(n);
    order_.resize(n);
    xs_.resize(n);
    ys_.resize(n);
    zs_.resize(n);
    for (std::size_t i = 0; i < n; ++i) cell_of_[i] = cell_index(pos[i]);
    std::fill(cell_start_.begin(), cell_start_.end(), 0);
    for (std::size_t i = 0; i < n; ++i) ++cell_start_[cell_of_[i] + 1];
    for (std::size_t c = 1; c < cell_start_.size(); ++c) cell_start_[c] += cell_start_[c - 1];
    cursor_.assign(cell_start_.begin(), cell_start_.end() - 1);
    for (std::size_t i = 0; i < n; ++i) {
      const Index s = cursor_[cell_of_[i]]++;
      order_[s] = static_cast<Index>(i);
      xs_[s] = pos[i].x;
      ys_[s] = pos[i].y;
      zs_[s] = pos[i].z;
    }
  }

  double radius() const { return radius_; }
  std::span<const Index> order() const { return order_; }

  // `pos` is unused (the grid keeps its own copy); kept for CellList's signature.
  template <class F>
  TALUS_PAIR_INLINE void for_each_neighbour(const Vec3& x, std::span<const Vec3> /*pos*/, double radius, F&& f) const {
    if (periodic_[0] || periodic_[1] || periodic_[2])
      query<true>(x, radius, f);
    else
      query<false>(x, radius, f);
  }

 private:
  template <bool Periodic, class F>
  TALUS_PAIR_INLINE void query(const Vec3& x, double radius, F& f) const {
    const double r2max = radius * radius;
    const int reach = 2;  // cells are at least half the build radius; queries use at most that radius
    int c[3];
    for (int a = 0; a < 3; ++a) c[a] = axis_cell(x[a], a);
    const int zr = dim_ == 3 ? reach : 0;
    Hits hits;
    for (int dz = -zr; dz <= zr; ++dz) {
      int cz = c[2] + dz;
      double sz = 0.0;
      if (!wrap(cz, 2, sz)) continue;
      const double gz = dim_ == 3 ? gap(x.z, c[2] + dz, 2) : 0.0;
      if (gz * gz >= r2max) continue;
      for (int dy = -reach; dy <= reach; ++dy) {
        int cy = c[1] + dy;
        double sy = 0.0;
        if (!wrap(cy, 1, sy)) continue;
        const double gy = gap(x.y, c[1] + dy, 1);
        const double rest = r2max - gy * gy - gz * gz;
        if (rest <= 0.0) continue;
        // x-range of cells this row can contribute.
        const double w = std::sqrt(rest);
        int x0 = floor_within((x.x - w - lo_.x) * inv_cell_[0], c[0] - reach, c[0] + reach);
        int x1 = floor_within((x.x + w - lo_.x) * inv_cell_[0], c[0] - reach, c[0] + reach);
        const std::size_t row = (static_cast<std::size_t>(cz) * n_[1] + cy) * n_[0];
        if (!periodic_[0]) {
          // Points outside the grid sit in its edge cells: keep those in range.
          x0 = std::clamp(x0, 0, n_[0] - 1);
          x1 = std::clamp(x1, 0, n_[0] - 1);
          if (x0 > x1) continue;
          const int image = Periodic ? record_image(hits, 0.0, sy, sz) : 0;
          scan<Periodic>(row + x0, row + x1 + 1, x, image, r2max, hits, f);
        } else {
          for (int k = x0; k <= x1; ++k) {
            int cx = k;
            double sx = 0.0;
            wrap(cx, 0, sx);
            scan<Periodic>(row + cx, row + cx + 1, x, record_image(hits, sx, sy, sz), r2max, hits, f);
          }
        }
      }
    }
    flush<Periodic>(hits, x, f);
  }

  static constexpr int chunk = 64;
  // Hits of one query: sorted index and which periodic image (shift) it was
  // found in; without periodic axes every shift is zero and is not stored.
  struct Hits {
    Index s[chunk];
    std::uint8_t image[chunk];

    Vec3 shift[27];
    int count = 0;
  };
  template <bool Periodic, class F>
  TALUS_PAIR_INLINE void flush(Hits& h, const Vec3& x, F& f) const {
    for (int k = 0; k < h.count; ++k) {
      const Index s = h.s[k];
      Vec3 q = x;
      if constexpr (Periodic) q -= h.shift[h.image[k]];
      const Vec3 dx{q.x - xs_[s], q.y - ys_[s], q.z - zs_[s]};
      f(order_[s], dx, dx.x * dx.x + dx.y * dx.y + dx.z * dx.z);
    }
    h.count = 0;
  }

  // The periodic image a shift belongs to: one of 27 (-L, 0, +L per axis).
  static int record_image(Hits& hits, double sx, double sy, double sz) {
    auto sign = [](double v) { return v < 0.0 ? 0 : (v > 0.0 ? 2 : 1); };
    const int id = sign(sx) + 3 * sign(sy) + 9 * sign(sz);
    hits.shift[id] = Vec3{sx, sy, sz};
    return id;
  }

  // Tests the sorted points of cells [c0, c1) without a branch on the
  // outcome; flushes full chunks to f.
  template <bool Periodic, class F>
  TALUS_PAIR_INLINE void scan(std::size_t c0, std::size_t c1, const Vec3& x, int image, double r2max, Hits& hits, F& f) const {
    const Index e = cell_start_[c1];
    Vec3 q = x;
    if constexpr (Periodic) q -= hits.shift[image];
    // The count lives in a register: kept in `hits`, every candidate would wait on a store and reload.
    int count = hits.count;
    for (Index s = cell_start_[c0]; s < e; ++s) {
      const double dx = q.x - xs_[s], dy = q.y - ys_[s], dz = q.z - zs_[s];
      const double r2 = dx * dx + dy * dy + dz * dz;
      hits.s[count] = s;
      if constexpr (Periodic) hits.image[count] = static_cast<std::uint8_t>(image);
      count += r2 < r2max ? 1 : 0;
      if (count == chunk) {
        hits.count = count;
        flush<Periodic>(hits, x, f);
        count = 0;
      }
    }
    hits.count = count;
  }

  // Distance along axis a from v to the slab of (unwrapped) cell k; 0 inside.
  // The edge cells of a closed axis extend to infinity (they hold the points
  // clamped into them).
  double gap(double v, int k, int a) const {
    const double c0 = lo_[a] + k * cell_[a], c1 = c0 + cell_[a];
    const bool open_below = !periodic_[a] && k <= 0, open_above = !periodic_[a] && k >= n_[a] - 1;
    if (v < c0 && !open_below) return c0 - v;
    if (v > c1 && !open_above) return v - c1;
    return 0.0;
  }
  int axis_cell(double v, int a) const {
    if (a >= dim_) return 0;
    return floor_within((v - lo_[a]) * inv_cell_[a], 0, n_[a] - 1);
  }
  Index cell_index(const Vec3& p) const {
    return static_cast<Index>((static_cast<std::size_t>(axis_cell(p.z, 2)) * n_[1] + axis_cell(p.y, 1)) * n_[0] +
                              axis_cell(p.x, 0));
  }
  bool wrap(int& k, int a, double& shift) const {
    if (k >= 0 && k < n_[a]) return true;
    if (!periodic_[a]) return false;
    if (k < 0) {
      k += n_[a];
      shift = -period_[a];
    } else {
      k -= n_[a];
      shift = period_[a];
    }
    return true;
  }

  int dim_ = 3;
  Vec3 lo_{};
  double radius_ = 0.0;
  std::array<bool, 3> periodic_{};
  std::array<int, 3> n_{1, 1, 1};
  std::array<double, 3> cell_{1, 1, 1}, inv_cell_{1, 1, 1}, period_{0, 0, 0};
  std::vector<Index> cell_start_, cursor_, cell_of_, order_;
  std::vector<double> xs_, ys_, zs_;
};

}  // namespace talus::sph
