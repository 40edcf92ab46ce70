// Plan-view (2D) neighbour search for particles whose search radii differ by
// orders of magnitude, as at a thinning run-out front where the smoothing
// length grows while the bulk keeps the scene's h. One grid sized by the
// largest radius makes every particle scan the cells a handful of front
// particles need; here particles are binned into levels by radius (level k
// holds radii in (base 2^(k-1), base 2^k], level 0 everything up to base),
// each level on its own grid with cells half the level's bound. A query
// visits, per level, only the cells its reach overlaps, so it finds
// exactly the pairs a single coarse grid would find (r < reach), at a cost
// set by the local radii.
//
//   gather query     reach = own radius                (sums at x_i with l_i)
//   symmetric query  reach = max(own radius, level max) (pairs with r < max(R_i, R_j))
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <span>
#include <string>
#include <vector>

#include "talus/config.hpp"
#include "talus/error.hpp"
#include "talus/vec3.hpp"

namespace talus::runout {

class LevelGrid {
 public:
  static constexpr int max_levels = 24;

  // lo/hi bound every binned position (along a periodic axis: the period).
  // `base` is the largest search radius of level 0, typically the kernel support of the
  // scene's smoothing length.
  void configure(Vec3 lo, Vec3 hi, std::array<bool, 3> periodic, double base) {
    lo_ = lo;
    length_ = {hi.x - lo.x, hi.y - lo.y};
    periodic_ = {periodic[0], periodic[1]};
    base_ = base;
    levels_ = 0;
    cell_start_.clear();
  }

  // Bins positions by (level of radius[i], cell). Grids are laid out the first
  // time a level is used; nothing allocates once the particle count and the
  // number of levels are stable.
  void build(std::span<const Vec3> pos, std::span<const double> radius) {
    const std::size_t n = pos.size();
    key_.resize(n);
    order_.resize(n);
    int top = 0;
    for (std::size_t i = 0; i < n; ++i) top = std::max(top, level_of(radius[i]));
    if (top >= levels_) add_levels(top + 1);
    std::fill(level_max_.begin(), level_max_.end(), 0.0);
    std::fill(cell_start_.begin(), cell_start_.end(), 0);
    for (std::size_t i = 0; i < n; ++i) {
      const int k = level_of(radius[i]);
      const Level& L = level_[k];
      level_max_[k] = std::max(level_max_[k], radius[i]);
      key_[i] = static_cast<Index>(L.offset + L.cell(pos[i], lo_));
      ++cell_start_[key_[i] + 1];
    }
    for (std::size_t c = 1; c < cell_start_.size(); ++c) cell_start_[c] += cell_start_[c - 1];
    cursor_.assign(cell_start_.begin(), cell_start_.end() - 1);
    for (std::size_t i = 0; i < n; ++i) order_[cursor_[key_[i]]++] = static_cast<Index>(i);
  }

  // Calls f(j, dx, r2) for every binned j with r = |x - x_j| < reach, where
  // dx = x - x_j (on periodic axes: once for each image of j within reach)
  // and reach = own (gather) or max(own, the largest radius of j's level)
  // (symmetric: the caller then keeps r < max(R_i, R_j)).
  template <class F>
  void for_each_neighbour(const Vec3& x, std::span<const Vec3> pos, double own, bool symmetric, F&& f) const {
    for (int k = 0; k < levels_; ++k) {
      if (level_max_[k] <= 0.0) continue;  // empty level
      const double reach = symmetric ? std::max(own, level_max_[k]) : own;
      visit(level_[k], x, pos, reach, f);
    }
  }

  double largest_radius() const {
    double m = 0.0;
    for (int k = 0; k < levels_; ++k) m = std::max(m, level_max_[k]);
    return m;
  }

 private:
  struct Level {
    std::array<int, 2> n{1, 1};
    std::array<double, 2> inv{1.0, 1.0};
    std::size_t offset = 0;
    int axis_cell(double v, double lo, int a) const {
      return std::clamp(static_cast<int>(std::floor((v - lo) * inv[a])), 0, n[a] - 1);
    }
    std::size_t cell(const Vec3& p, const Vec3& lo) const {
      return static_cast<std::size_t>(axis_cell(p.y, lo.y, 1)) * n[0] + axis_cell(p.x, lo.x, 0);
    }
  };

  int level_of(double r) const {
    if (!(r > base_)) return 0;
    const int k = static_cast<int>(std::ceil(std::log2(r / base_) - 1e-12));
    if (k >= max_levels)
      throw RunError("neighbour search: a search radius of " + std::to_string(r) + " m exceeds 2^" +
                     std::to_string(max_levels) + " times the scene's (" + std::to_string(base_) + " m)");
    return std::max(k, 0);
  }

  void add_levels(int count) {
    level_.resize(count);
    level_max_.assign(count, 0.0);
    std::size_t total = 0;
    for (int k = 0; k < count; ++k) {
      Level& L = level_[k];
      // Cells of half the level's largest radius: a query scans (2 R + cell)^2.
      const double cell = 0.5 * base_ * std::ldexp(1.0, k);
      for (int a = 0; a < 2; ++a) {
        L.n[a] = std::max(1, static_cast<int>(std::floor(length_[a] / cell)));
        // Bounded grids: a level never needs more cells than particles could fill usefully.
        L.n[a] = std::min(L.n[a], 4096);
        L.inv[a] = L.n[a] / length_[a];
      }
      L.offset = total;
      total += static_cast<std::size_t>(L.n[0]) * L.n[1];
    }
    levels_ = count;
    cell_start_.assign(total + 1, 0);
  }

  // Visits the cells within `reach` of x. Along a periodic axis the cell
  // stencil is taken unwrapped, so each image of a cell is visited once with
  // its own shift, which stays right even when the reach exceeds half the period.
  template <class F>
  void visit(const Level& L, const Vec3& x, std::span<const Vec3> pos, double reach, F& f) const {
    const double r2max = reach * reach;
    // The cells [x - reach, x + reach] overlaps, unwrapped on periodic axes.
    std::array<int, 2> first{}, last{};
    for (int a = 0; a < 2; ++a) {
      first[a] = static_cast<int>(std::floor((x[a] - reach - lo_[a]) * L.inv[a]));
      last[a] = static_cast<int>(std::floor((x[a] + reach - lo_[a]) * L.inv[a]));
      if (!periodic_[a]) {
        first[a] = std::clamp(first[a], 0, L.n[a] - 1);
        last[a] = std::clamp(last[a], 0, L.n[a] - 1);
      }
    }
    for (int cy = first[1]; cy <= last[1]; ++cy) {
      int ry = cy;
      double sy = 0.0;
      if (!wrap(ry, 1, L, sy)) continue;
      const std::size_t row = L.offset + static_cast<std::size_t>(ry) * L.n[0];
      if (!periodic_[0]) {
        // The cells of a row are contiguous: one range of particles.
        scan(row + first[0], row + last[0] + 1, x, pos, r2max, Vec3{0.0, sy, 0.0}, f);
      } else {
        for (int cx = first[0]; cx <= last[0]; ++cx) {
          int rx = cx;
          double sx = 0.0;
          wrap(rx, 0, L, sx);
          scan(row + rx, row + rx + 1, x, pos, r2max, Vec3{sx, sy, 0.0}, f);
        }
      }
    }
  }

  // Wraps a cell coordinate along a periodic axis; the shift is added to x_j
  // so that x - (x_j + shift) is that image's offset. False off a closed axis.
  bool wrap(int& k, int a, const Level& L, double& shift) const {
    if (k >= 0 && k < L.n[a]) return true;
    if (!periodic_[a]) return false;
    const int image = static_cast<int>(std::floor(static_cast<double>(k) / L.n[a]));
    k -= image * L.n[a];
    shift = image * length_[a];
    return true;
  }

  template <class F>
  void scan(std::size_t c0, std::size_t c1, const Vec3& x, std::span<const Vec3> pos, double r2max,
            const Vec3& shift, F& f) const {
    for (Index s = cell_start_[c0], e = cell_start_[c1]; s < e; ++s) {
      const Index j = order_[s];
      const Vec3 dx{x.x - (pos[j].x + shift.x), x.y - (pos[j].y + shift.y), 0.0};
      const double r2 = dx.x * dx.x + dx.y * dx.y;
      if (r2 < r2max) f(j, dx, r2);
    }
  }

  Vec3 lo_{};
  std::array<double, 2> length_{1.0, 1.0};
  std::array<bool, 2> periodic_{};
  double base_ = 1.0;
  int levels_ = 0;
  std::vector<Level> level_;
  std::vector<double> level_max_;
  std::vector<Index> cell_start_, cursor_, key_, order_;
};

}  // namespace talus::runout
