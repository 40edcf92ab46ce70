#include "h5_ranks.hpp"

#include <stdexcept>

#include "talus/parallel.hpp"

namespace talus::writers::h5 {

#ifdef TALUS_PARALLEL_HDF5

bool shared_files() { return true; }

Handle shared_file_access(const Parallel& ranks, const std::string& path) {
  Handle list(check(H5Pcreate(H5P_FILE_ACCESS), "cannot set up parallel access to", path), H5Pclose);
  check(H5Pset_fapl_mpio(list, MPI_Comm_f2c(ranks.communicator()), MPI_INFO_NULL),
        "cannot set up parallel access to", path);
  return list;
}

Handle collective_transfer(const std::string& path) {
  Handle list(check(H5Pcreate(H5P_DATASET_XFER), "cannot set up a collective write to", path), H5Pclose);
  check(H5Pset_dxpl_mpio(list, H5FD_MPIO_COLLECTIVE), "cannot set up a collective write to", path);
  return list;
}

#else

bool shared_files() { return false; }

Handle shared_file_access(const Parallel&, const std::string&) {
  throw std::logic_error("h5::shared_file_access: this build's HDF5 is the serial flavour");
}
Handle collective_transfer(const std::string&) {
  throw std::logic_error("h5::collective_transfer: this build's HDF5 is the serial flavour");
}

#endif

}  // namespace talus::writers::h5
