// Checkpoint files: the complete state of a run (every particle field of
// both stores, the blocks, the clock, the opaque state of the stages and of
// the boundary models, and the output schedule) so that a restart continues
// bit for bit. Binary, little-endian, written to a temporary name and renamed.
#pragma once

#include "talus/config.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace talus {

class World;
namespace ranks {
class Host;
}

struct RunState {
  std::uint64_t scene_hash = 0;  // the restart must use the same scene text
  std::vector<std::string> stage_states;
  std::vector<std::string> boundary_states;  // each boundary model once, in the order of the bodies naming it
  std::vector<double> writer_next_time;
  std::vector<std::uint64_t> writer_next_step;
  double last_output_time = -1.0;
};

TALUS_API void save_checkpoint(const std::string& path, const World& world, const RunState& state);
// The same file written by the ranks together (checkpoint_ranks.cpp): each
// rank its owned rows of every field, in rank order; rank 0 the rest, with
// `state` and the blocks as it holds them.
TALUS_API void save_checkpoint_on_ranks(const std::string& path, const World& world, const RunState& state,
                                        const ranks::Host& ranks);
// Replaces the world's state with the checkpoint's. Throws InputError naming
// the file if it is not a checkpoint of this scene. With `ranks`, each rank
// reads an equal share of the particles (the file may come from any number
// of ranks) and checksums an equal share of the bytes.
TALUS_API RunState load_checkpoint(const std::string& path, World& world, std::uint64_t scene_hash,
                                   const ranks::Host* ranks = nullptr);

TALUS_API std::uint64_t text_hash(const std::string& text);  // FNV-1a, stable across builds

}  // namespace talus
