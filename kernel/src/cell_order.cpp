#include "cell_order.hpp"

#include <array>

#include "talus/neighbour_grid.hpp"

namespace talus {

std::vector<Index> cell_order(std::span<const Vec3> x, const Vec3& lo, const Vec3& hi, double cell, int dim) {
  // The neighbour grid's cell counts: at most 2^24 cells, however far apart the points.
  std::array<int, 3> n{1, 1, 1};
  for (int a = 0; a < dim && a < 3; ++a) n[a] = cells_along(hi[a] - lo[a], cell);
  fit_cells(n);
  std::array<double, 3> inv{0, 0, 0};
  for (int a = 0; a < dim && a < 3; ++a) inv[a] = n[a] / (hi[a] - lo[a]);
  auto axis = [&](double v, int a) -> std::size_t {
    return a < dim ? static_cast<std::size_t>(floor_within((v - lo[a]) * inv[a], 0, n[a] - 1)) : 0;
  };
  auto key = [&](const Vec3& p) { return (axis(p.z, 2) * n[1] + axis(p.y, 1)) * n[0] + axis(p.x, 0); };
  // Each key is computed twice rather than stored: a re-sort is rare, and a
  // key per point would add to the run's peak memory.
  std::vector<Index> start(static_cast<std::size_t>(n[0]) * n[1] * n[2] + 1, 0);
  for (const Vec3& p : x) ++start[key(p) + 1];
  for (std::size_t c = 1; c < start.size(); ++c) start[c] += start[c - 1];
  std::vector<Index> order(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) order[start[key(x[i])]++] = static_cast<Index>(i);
  return order;
}

}  // namespace talus
