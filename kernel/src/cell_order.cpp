#include "cell_order.hpp"

#include <algorithm>
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
  // Two stable counting sorts, by row of cells (z, y), then each row by
  // column (x): the order of one sort by cell, with a count per row and per
  // column instead of one per cell. The cells are computed again rather than
  // stored: a re-sort is rare, and what it holds adds to the run's peak memory.
  auto row = [&](const Vec3& p) { return axis(p.z, 2) * n[1] + axis(p.y, 1); };
  std::vector<Index> start(static_cast<std::size_t>(n[1]) * n[2] + 1, 0);
  for (const Vec3& p : x) ++start[row(p) + 1];
  for (std::size_t r = 1; r < start.size(); ++r) start[r] += start[r - 1];
  std::vector<Index> order(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) order[start[row(x[i])]++] = static_cast<Index>(i);
  std::copy_backward(start.begin(), start.end() - 2, start.end() - 1);  // each cursor ended at the next row's start
  start[0] = 0;
  std::vector<Index> column(static_cast<std::size_t>(n[0]) + 1), in_row;
  for (std::size_t r = 0; r + 1 < start.size(); ++r) {
    const auto first = order.begin() + start[r], last = order.begin() + start[r + 1];
    in_row.assign(first, last);
    std::fill(column.begin(), column.end(), 0);
    for (const Index i : in_row) ++column[axis(x[i].x, 0) + 1];
    for (std::size_t c = 1; c < column.size(); ++c) column[c] += column[c - 1];
    for (const Index i : in_row) first[column[axis(x[i].x, 0)]++] = i;
  }
  return order;
}

}  // namespace talus
