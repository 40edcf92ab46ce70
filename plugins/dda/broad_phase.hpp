// Broad phase over the blocks' bounding boxes. Blocks no larger than the
// largest moving block go into a uniform grid of that cell size, keyed by
// the cell of their box centre: two overlapping boxes then sit in the same
// or a neighbouring cell. Larger blocks (bedrock, walls, slopes) are tested
// against every box. Candidate pairs come out as (i, j) with i < j, sorted,
// so that the contact list (and the run) does not depend on the thread count.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "talus/vec3.hpp"

namespace talus::dda {

class BroadPhase {
 public:
  // `active[i]` false for blocks that never move (fixed, or kinematic): pairs
  // of two inactive blocks are skipped. Boxes must already include the margin.
  void find_pairs(const std::vector<Vec3>& lo, const std::vector<Vec3>& hi, const std::vector<std::uint8_t>& active,
                  std::vector<std::pair<std::uint32_t, std::uint32_t>>& pairs);

 private:
  std::vector<std::uint32_t> large_;
  std::vector<std::pair<std::uint64_t, std::uint32_t>> cells_;  // (cell key, block), sorted
  // Open-addressing table: cell key -> first index in cells_ (empty: start = ~0).
  std::vector<std::pair<std::uint64_t, std::uint32_t>> table_;
};

}  // namespace talus::dda
