// Rigid-block states in the HDF5 output: one group Blocks/Step#N per frame
// beside the particles' Step#N (outside the H5Part steps, so ParaView's H5Part
// reader ignores it). Shapes go into every frame so that each is
// self-contained and preview tools can outline the blocks.
#pragma once

#include <hdf5.h>

#include <cstdint>
#include <string>

namespace talus {
class BlockSet;
}

namespace talus::writers {

void write_block_states(hid_t file, const BlockSet& blocks, std::uint64_t index, double time, std::uint64_t step,
                        const std::string& path);

}  // namespace talus::writers
