// Which ranks this process is one of. The MPI side lives in
// libtalus_ranks_mpi (mpi/ranks_mpi.cpp), loaded from libtalus' own folder
// when mpirun started this process; otherwise the process is rank 0 of 1
// and maps none of MPI.
#include "ranks.hpp"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "library_folder.hpp"
#include "talus/error.hpp"

namespace talus::ranks {

namespace {

const Backend* backend = nullptr;

bool started_by_mpirun() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"})
    if (std::getenv(name)) return true;
  return false;
}

#if TALUS_WITH_MPI
// Global symbols: Open MPI's own components, which it opens in turn, look
// for libmpi's symbols there.
const Backend* load_backend() {
  const std::filesystem::path folder = library_folder();
  if (folder.empty())
    throw InputError("error: started by mpirun, but the folder of libtalus is unknown (dladdr failed)");
  const std::filesystem::path library = folder / TALUS_RANKS_MPI_LIBRARY;
  void* handle = dlopen(library.c_str(), RTLD_NOW | RTLD_GLOBAL);
  if (!handle)
    throw InputError("error: started by mpirun, but the MPI side of Talus does not load: " +
                     std::string(dlerror()));
  using Entry = const Backend* (*)();
  const auto entry = reinterpret_cast<Entry>(dlsym(handle, "talus_ranks_backend"));
  if (!entry) throw InputError("error: " + library.string() + " has no talus_ranks_backend");
  return entry();
}
#endif

}  // namespace

void start(int* argc, char*** argv) {
  if (backend || !started_by_mpirun()) return;
#if TALUS_WITH_MPI
  backend = load_backend();
  backend->start(argc, argv);
#else
  (void)argc;
  (void)argv;
#endif
}

void stop() {
  if (backend) backend->stop();
}

int rank() { return backend ? backend->rank() : 0; }

int count() { return backend ? backend->count() : 1; }

void abort_all(int code) {
  if (backend) backend->abort_all(code);
  std::exit(code);
}

std::unique_ptr<Host> make_host(const World& world, double cell, double halo_reach, const std::string& partition) {
  if (count() < 2) return nullptr;
  return backend->make_host(world, cell, halo_reach, partition);
}

}  // namespace talus::ranks
