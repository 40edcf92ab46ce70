// The contacts and blocks at the end of a trial, kept for the two trials
// that bound the safety factor (the last that held, the first that failed),
// and written to HDF5: per contact its point, normal, force split into normal
// and shear parts, area, gap, state and blocks; per block its pose and
// displacement from the gravity-loaded state.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "contact_set.hpp"
#include "talus/blocks.hpp"
#include "trial_log.hpp"

namespace talus::strength_reduction {

struct LimitState {
  bool present = false;
  double factor = 0.0;
  std::int64_t steps = 0;
  double ratio = 0.0;
  std::vector<Vec3> point, normal, force;
  std::vector<double> normal_force, shear_force, area, gap;
  std::vector<std::uint8_t> state, bonded;
  std::vector<std::uint32_t> block_a, block_b;
  std::vector<Vec3> position, displacement;
  std::vector<Quaternion> orientation;
  std::vector<std::uint8_t> released;  // per block: held by open or slipping joints only (or moved_beyond)
};

// rigid_body: as for released_blocks.
LimitState capture(const TrialResult& trial, const dda::ContactSet& contacts, const BlockSet& blocks,
                   const std::vector<Vec3>& start_position, const std::vector<std::uint32_t>& rigid_body);

// A collapse needs no slip path: marks as released the blocks of the failing
// trial that moved farther than any block of the holding one (the two trials
// at the final bracket), and returns the largest displacement that held.
double release_moved_blocks(LimitState& failed, const LimitState& stable);

// Groups /stable and /failed (each when present), block names at the root.
// Written to `path`.tmp and renamed.
void write_limit_state(const std::string& path, const BlockSet& blocks, const LimitState& stable,
                       const LimitState& failed);

}  // namespace talus::strength_reduction
