// HDF5 property lists for one file that several MPI ranks write together
// (parallel HDF5, Debian's libhdf5-openmpi-dev). A build whose HDF5 is the
// serial flavour cannot: shared_files() is false there and the host gathers
// the particles to rank 0 instead (Writer::writes_on_every_rank).
#pragma once

#include "h5_util.hpp"

namespace talus {
class Parallel;
}

namespace talus::writers::h5 {

bool shared_files();
// File access through MPI-IO over the ranks' communicator.
Handle shared_file_access(const Parallel& ranks, const std::string& path);
// Data transfer in which every rank takes part (each with its own rows).
Handle collective_transfer(const std::string& path);

}  // namespace talus::writers::h5
