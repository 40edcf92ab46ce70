// Cell-linked-list neighbour search, 2D and 3D, with periodic axes.
// Particles are binned by a counting sort into cells of edge >= the search
// radius; `order()` gives the cell-sorted permutation the host applies to the
// particle store periodically for cache locality. Queries are header-only
// templates so the caller's lambda inlines into the traversal; nothing
// allocates after the first build at a given size.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <span>
#include <string>
#include <vector>

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

// Halves the axis with the most cells until the grid has at most 2^24 cells
// (an Index numbers them, cell_start_ holds them). Particles far apart, such
// as a wall spaced 1e19 m, asked for more cells than a size_t counts; coarser
// cells than asked are still correct, only slower. An axis keeps `least`.
inline void fit_cells(std::array<int, 3>& n, int least) {
  constexpr double most = 1 << 24;
  while (static_cast<double>(n[0]) * n[1] * n[2] > most) {
    int a = 0;
    for (int b = 1; b < 3; ++b)
      if (n[b] > n[a]) a = b;
    if (n[a] / 2 < least) break;
    n[a] /= 2;
  }
}

// floor(s) as an int within [lo, hi]; clamped before the conversion, which
// is undefined for what an int cannot hold (a point far outside the grid).
// NaN gives lo.
inline int floor_within(double s, int lo, int hi) {
  const double k = std::floor(s);
  return k > lo ? (k < hi ? static_cast<int>(k) : hi) : lo;
}

// A length for a message: 4 significant digits (std::to_string prints 1e308 with 309).
inline std::string short_number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", v);
  return text;
}

class CellList {
 public:
  // lo/hi bound every position that will be binned; along a periodic axis they
  // are the period. `cell_size` is at least the largest search radius.
  void configure(int dim, Vec3 lo, Vec3 hi, double cell_size, std::array<bool, 3> periodic = {}) {
    dim_ = dim;
    lo_ = lo;
    periodic_ = periodic;
    for (int a = 0; a < 3; ++a) {
      const double length = hi[a] - lo[a];
      if (a >= dim) {
        n_[a] = 1;
        cell_[a] = 1.0;
        period_[a] = 0.0;
        continue;
      }
      n_[a] = cells_along(length, cell_size);
      if (periodic[a] && n_[a] < 3)
        throw InputError("error: the periodic domain axis " + std::string(1, static_cast<char>('x' + a)) + " spans " +
                         short_number(length) + " m, less than 3 search radii (3 x " + short_number(cell_size) +
                         " m): enlarge the domain along it or refine dp");
    }
    fit_cells(n_, 3);
    for (int a = 0; a < dim && a < 3; ++a) {
      cell_[a] = (hi[a] - lo[a]) / n_[a];
      period_[a] = periodic[a] ? hi[a] - lo[a] : 0.0;
    }
    inv_cell_ = {1.0 / cell_[0], 1.0 / cell_[1], 1.0 / cell_[2]};
    radius_ = cell_size;
    cell_start_.assign(static_cast<std::size_t>(n_[0]) * n_[1] * n_[2] + 1, 0);
  }

  // Bins positions; afterwards `order()` lists particle indices by cell.
  void build(std::span<const Vec3> pos) {
    const std::size_t n = pos.size();
    cell_of_.resize(n);
    order_.resize(n);
#pragma omp parallel for schedule(static) if (n > 4096)
    for (std::size_t i = 0; i < n; ++i) cell_of_[i] = cell_index(pos[i]);
    std::fill(cell_start_.begin(), cell_start_.end(), 0);
    for (std::size_t i = 0; i < n; ++i) ++cell_start_[cell_of_[i] + 1];
    for (std::size_t c = 1; c < cell_start_.size(); ++c) cell_start_[c] += cell_start_[c - 1];
    cursor_.assign(cell_start_.begin(), cell_start_.end() - 1);
    for (std::size_t i = 0; i < n; ++i) order_[cursor_[cell_of_[i]]++] = static_cast<Index>(i);
  }

  std::span<const Index> order() const { return order_; }
  int dim() const { return dim_; }
  double radius() const { return radius_; }
  std::array<int, 3> cells() const { return n_; }

  // Calls f(j, dx, r2) for every binned particle j with |x - x_j| < radius,
  // where dx = x - x_j (minimum image along periodic axes). `pos` are the
  // positions given to build(). The point itself is reported too if binned.
  template <class F>
  void for_each_neighbour(const Vec3& x, std::span<const Vec3> pos, double radius, F&& f) const {
    const double r2max = radius * radius;
    std::array<int, 3> c{};
    for (int a = 0; a < 3; ++a) c[a] = axis_cell(x[a], a);
    const int zr = dim_ == 3 ? 1 : 0;
    for (int dz = -zr; dz <= zr; ++dz) {
      double sz = 0.0;
      int cz = c[2] + dz;
      if (!wrap(cz, 2, sz)) continue;
      for (int dy = -1; dy <= 1; ++dy) {
        double sy = 0.0;
        int cy = c[1] + dy;
        if (!wrap(cy, 1, sy)) continue;
        const std::size_t row = (static_cast<std::size_t>(cz) * n_[1] + cy) * n_[0];
        if (!periodic_[0] || n_[0] < 3) {
          // The x-neighbour cells are contiguous in memory: one range.
          const int x0 = std::max(c[0] - 1, 0), x1 = std::min(c[0] + 1, n_[0] - 1);
          visit(row + x0, row + x1 + 1, x, pos, r2max, Vec3{0.0, sy, sz}, f);
        } else {
          for (int dx = -1; dx <= 1; ++dx) {
            double sx = 0.0;
            int cx = c[0] + dx;
            wrap(cx, 0, sx);
            visit(row + cx, row + cx + 1, x, pos, r2max, Vec3{sx, sy, sz}, f);
          }
        }
      }
    }
  }

  // Minimum-image difference a - b along periodic axes.
  Vec3 difference(const Vec3& a, const Vec3& b) const {
    Vec3 d = a - b;
    for (int k = 0; k < dim_; ++k)
      if (periodic_[k]) d[k] -= period_[k] * std::round(d[k] / period_[k]);
    return d;
  }

 private:
  int axis_cell(double v, int a) const {
    if (a >= dim_) return 0;
    return floor_within((v - lo_[a]) * inv_cell_[a], 0, n_[a] - 1);
  }
  Index cell_index(const Vec3& p) const {
    return static_cast<Index>((static_cast<std::size_t>(axis_cell(p.z, 2)) * n_[1] + axis_cell(p.y, 1)) * n_[0] +
                              axis_cell(p.x, 0));
  }
  // Wraps a neighbour cell coordinate; the shift is added to x_j so that
  // x - (x_j + shift) is the minimum image. False if outside a closed axis.
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
  template <class F>
  void visit(std::size_t c0, std::size_t c1, const Vec3& x, std::span<const Vec3> pos, double r2max,
             const Vec3& shift, F& f) const {
    for (Index s = cell_start_[c0], e = cell_start_[c1]; s < e; ++s) {
      const Index j = order_[s];
      const Vec3 dx = x - (pos[j] + shift);
      const double r2 = norm2(dx);
      if (r2 < r2max) f(j, dx, r2);
    }
  }

  int dim_ = 3;
  Vec3 lo_{};
  std::array<bool, 3> periodic_{};
  std::array<int, 3> n_{1, 1, 1};
  std::array<double, 3> cell_{1, 1, 1}, inv_cell_{1, 1, 1}, period_{0, 0, 0};
  double radius_ = 0.0;
  std::vector<Index> cell_start_, cursor_, cell_of_, order_;
};

}  // namespace talus
