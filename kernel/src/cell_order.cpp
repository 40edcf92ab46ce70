#include "cell_order.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

namespace talus {

std::vector<Index> cell_order(std::span<const Vec3> x, const Vec3& lo, const Vec3& hi, double cell, int dim) {
  std::array<std::size_t, 3> n{1, 1, 1};
  std::array<double, 3> inv{0, 0, 0};
  for (int a = 0; a < dim && a < 3; ++a) {
    n[a] = static_cast<std::size_t>(std::clamp(std::ceil((hi[a] - lo[a]) / cell), 1.0, 1e6));
    inv[a] = n[a] / (hi[a] - lo[a]);
  }
  auto axis = [&](double v, int a) {
    const double c = std::floor((v - lo[a]) * inv[a]);
    return static_cast<std::size_t>(std::clamp(c, 0.0, static_cast<double>(n[a] - 1)));
  };
  std::vector<std::uint32_t> key(x.size());
  std::vector<Index> start(n[0] * n[1] * n[2] + 1, 0);
  for (std::size_t i = 0; i < x.size(); ++i) {
    const std::size_t cz = dim == 3 ? axis(x[i].z, 2) : 0, cy = dim >= 2 ? axis(x[i].y, 1) : 0;
    key[i] = static_cast<std::uint32_t>((cz * n[1] + cy) * n[0] + axis(x[i].x, 0));
    ++start[key[i] + 1];
  }
  for (std::size_t c = 1; c < start.size(); ++c) start[c] += start[c - 1];
  std::vector<Index> order(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) order[start[key[i]]++] = static_cast<Index>(i);
  return order;
}

}  // namespace talus
