// The released part of a block system: blocks not connected to the fixed
// blocks through joints that stick (the blocks of a clump count as connected).
// A group of free blocks held only by open or slipping joints has a
// through-going slip path around it.
#pragma once

#include <cstdint>
#include <vector>

#include "contact_set.hpp"
#include "talus/blocks.hpp"

namespace talus::strength_reduction {

struct Release {
  std::vector<std::uint32_t> blocks;  // indices of the released blocks, ascending
  double mass_fraction = 0.0;         // of the free blocks' mass
};

// rigid_body[i]: the block that leads block i's rigid body (DdaStage::rigid_body).
Release released_blocks(const BlockSet& blocks, const dda::ContactSet& contacts,
                        const std::vector<std::uint32_t>& rigid_body);

}  // namespace talus::strength_reduction
