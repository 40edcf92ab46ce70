#include "broad_phase.hpp"

#include <algorithm>
#include <cmath>

namespace talus::dda {
namespace {

bool overlap(const Vec3& alo, const Vec3& ahi, const Vec3& blo, const Vec3& bhi) {
  return alo.x <= bhi.x && blo.x <= ahi.x && alo.y <= bhi.y && blo.y <= ahi.y && alo.z <= bhi.z && blo.z <= ahi.z;
}

constexpr int key_bits = 21;
constexpr std::int64_t key_offset = 1 << (key_bits - 1);

std::uint64_t cell_key(std::int64_t i, std::int64_t j, std::int64_t k) {
  auto wrap = [](std::int64_t v) { return static_cast<std::uint64_t>((v + key_offset) & ((1 << key_bits) - 1)); };
  return (wrap(k) << (2 * key_bits)) | (wrap(j) << key_bits) | wrap(i);
}

}  // namespace

void BroadPhase::find_pairs(const std::vector<Vec3>& lo, const std::vector<Vec3>& hi,
                            const std::vector<std::uint8_t>& active,
                            std::vector<std::pair<std::uint32_t, std::uint32_t>>& pairs) {
  pairs.clear();
  const std::size_t n = lo.size();
  if (n < 2) return;
  // Cell size: the largest extent of a moving block.
  double cell = 0.0;
  for (std::size_t i = 0; i < n; ++i)
    if (active[i]) cell = std::max({cell, hi[i].x - lo[i].x, hi[i].y - lo[i].y, hi[i].z - lo[i].z});
  if (!(cell > 0.0)) return;
  const double inv = 1.0 / cell;
  large_.clear();
  cells_.clear();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 e = hi[i] - lo[i];
    if (e.x > cell || e.y > cell || e.z > cell) {
      large_.push_back(static_cast<std::uint32_t>(i));
      continue;
    }
    const Vec3 c = 0.5 * (lo[i] + hi[i]);
    cells_.emplace_back(cell_key(static_cast<std::int64_t>(std::floor(c.x * inv)),
                                 static_cast<std::int64_t>(std::floor(c.y * inv)),
                                 static_cast<std::int64_t>(std::floor(c.z * inv))),
                        static_cast<std::uint32_t>(i));
  }
  std::sort(cells_.begin(), cells_.end());
  std::size_t size = 16;
  while (size < 2 * cells_.size()) size *= 2;
  const std::size_t mask = size - 1;
  constexpr std::uint32_t empty = ~0u;
  table_.assign(size, {0, empty});
  auto slot = [&](std::uint64_t k) { return static_cast<std::size_t>((k * 0x9e3779b97f4a7c15ull) >> 20) & mask; };
  for (std::size_t s = 0; s < cells_.size(); ++s) {
    if (s > 0 && cells_[s].first == cells_[s - 1].first) continue;
    std::size_t h = slot(cells_[s].first);
    while (table_[h].second != empty) h = (h + 1) & mask;
    table_[h] = {cells_[s].first, static_cast<std::uint32_t>(s)};
  }
  // Each block against the later blocks of its cell and every block of the
  // 13 neighbour cells that come after its own (each cell pair once).
  for (std::size_t s = 0; s < cells_.size(); ++s) {
    const auto [key, i] = cells_[s];
    for (std::size_t t = s + 1; t < cells_.size() && cells_[t].first == key; ++t) {
      const std::uint32_t j = cells_[t].second;
      if ((active[i] || active[j]) && overlap(lo[i], hi[i], lo[j], hi[j])) pairs.emplace_back(std::min(i, j), std::max(i, j));
    }
    const Vec3 c = 0.5 * (lo[i] + hi[i]);
    const auto ci = static_cast<std::int64_t>(std::floor(c.x * inv)), cj = static_cast<std::int64_t>(std::floor(c.y * inv)),
               ck = static_cast<std::int64_t>(std::floor(c.z * inv));
    for (int dk = 0; dk <= 1; ++dk)
      for (int dj = (dk ? -1 : 0); dj <= 1; ++dj)
        for (int di = (dk || dj ? -1 : 1); di <= 1; ++di) {
          const std::uint64_t k = cell_key(ci + di, cj + dj, ck + dk);
          std::size_t h = slot(k);
          while (table_[h].second != empty && table_[h].first != k) h = (h + 1) & mask;
          if (table_[h].second == empty) continue;
          for (std::size_t t = table_[h].second; t < cells_.size() && cells_[t].first == k; ++t) {
            const std::uint32_t j = cells_[t].second;
            if ((active[i] || active[j]) && overlap(lo[i], hi[i], lo[j], hi[j]))
              pairs.emplace_back(std::min(i, j), std::max(i, j));
          }
        }
  }
  for (std::size_t s = 0; s < large_.size(); ++s) {
    const std::uint32_t i = large_[s];
    for (std::uint32_t j = 0; j < n; ++j) {
      if (j == i || (!active[i] && !active[j])) continue;
      const bool j_large = std::binary_search(large_.begin(), large_.end(), j);
      if (j_large && j < i) continue;  // each large-large pair once
      if (overlap(lo[i], hi[i], lo[j], hi[j])) pairs.emplace_back(std::min(i, j), std::max(i, j));
    }
  }
  std::sort(pairs.begin(), pairs.end());
}

}  // namespace talus::dda
