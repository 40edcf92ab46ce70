// Whether this process is one of several MPI ranks of one run, and what the
// host asks of the ranks (mpi/rank_exchange.hpp does it, in
// libtalus_ranks_mpi). A build without MPI, or a process not started by
// mpirun, is the single rank 0 of 1.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "talus/config.hpp"
#include "talus/parallel.hpp"
#include "talus/world.hpp"

namespace talus::ranks {

// MPI_Init when mpirun (or mpiexec) started this process; nothing otherwise.
TALUS_API void start(int* argc, char*** argv);
TALUS_API void stop();
TALUS_API int rank();
TALUS_API int count();
// After an error on one rank: stops every rank of the run with this exit code.
[[noreturn]] TALUS_API void abort_all(int code);

// One file several ranks write together, each its own bytes at its own offsets.
class SharedFile {
 public:
  virtual ~SharedFile() = default;
  // This rank alone.
  virtual void write_alone(std::uint64_t offset, std::span<const std::byte> bytes) = 0;
  // Collective: every rank calls it, each with its own offset and bytes (none too).
  virtual void write_together(std::uint64_t offset, std::span<const std::byte> bytes) = 0;
  // Collective; the bytes are in the file once it returns.
  virtual void close() = 0;
};

// The host's side of a run on several ranks: World::parallel() for the stages,
// and the moves between steps.
class Host : public Parallel {
 public:
  // Keeps this rank's share of the world every rank built whole, and makes the first cuts.
  // With `whole` false, each rank already holds a different share (a
  // checkpoint read in slices): only the cuts are made.
  virtual void distribute(World& world, bool whole) = 0;
  virtual void drop_halos(World& world) = 0;
  // Moves each particle to the owner of its place.
  virtual void migrate(World& world) = 0;
  // New cuts that share out `cost` (one per owned row: the fluid's, then the
  // boundary store's) evenly; moves every particle to its new owner.
  virtual void rebalance(World& world, std::span<const float> cost) = 0;
  virtual void build_halos(World& world) = 0;
  // Rank 0 holds a copy of every particle (for the writers) until release.
  virtual void gather_to_root(World& world) = 0;
  virtual void release_gathered(World& world) = 0;
  // Rank 0 gets every rank's texts, in rank order (its own first); the others get none.
  virtual std::vector<std::string> gather_texts(const std::vector<std::string>& mine) = 0;
  // Every rank gets every rank's values, in rank order (each rank gives as many).
  virtual std::vector<std::uint64_t> all_gather(std::span<const std::uint64_t> mine) const = 0;
  // Creates (or empties) `path` for a collective write; collective.
  virtual std::unique_ptr<SharedFile> create_shared_file(const std::string& path) const = 0;
};

// halo_reach: the search radius plus the skin particles may move before the
// next rebuild; partition: Zoltan's method ("RCB", "RIB" or "HSFC"). Null on
// a single rank.
TALUS_API std::unique_ptr<Host> make_host(const World& world, double cell, double halo_reach,
                                          const std::string& partition);

// What libtalus_ranks_mpi gives libtalus (its talus_ranks_backend()): the
// functions above as MPI does them, once this process is one of several.
struct Backend {
  void (*start)(int* argc, char*** argv);
  void (*stop)();
  int (*rank)();
  int (*count)();
  void (*abort_all)(int code);  // returns only where MPI is not running
  std::unique_ptr<Host> (*make_host)(const World& world, double cell, double halo_reach,
                                     const std::string& partition);
};

}  // namespace talus::ranks
