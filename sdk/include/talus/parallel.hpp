// What a stage or writer sees of a run spread over MPI ranks (DESIGN.md
// principle 9). Each rank owns the particles at the front of every store and
// holds halo copies of the other ranks' particles near its region behind them
// (particles.hpp). Positions and the other restart fields of the halo are
// fresh when a stage's step begins; a pass that reads a neighbour's field an
// earlier pass of the same step computed asks for it with refresh_halo().
// Without MPI, or on one rank, every call is the serial no-op below.
#pragma once

#include <cstdint>
#include <span>
#include <string>

#include "talus/config.hpp"
#include "talus/particles.hpp"

namespace talus {

class TALUS_API Parallel {
 public:
  virtual ~Parallel();

  virtual int rank() const { return 0; }
  virtual int ranks() const { return 1; }

  // Reductions over all ranks, summed in rank order: every rank gets the same
  // value, and it does not depend on message timing.
  virtual double sum(double local) const { return local; }
  virtual std::uint64_t sum(std::uint64_t local) const { return local; }
  // Element by element, in place, in one message (the same order rule).
  virtual void sum(std::span<double> local) const { (void)local; }
  virtual double max(double local) const { return local; }
  virtual double min(double local) const { return local; }
  // The sum of `local` over the ranks before this one: where this rank's rows
  // start in a file the ranks write together in rank order.
  virtual std::uint64_t sum_before(std::uint64_t local) const {
    (void)local;
    return 0;
  }
  // The ranks' communicator as MPI's Fortran handle (MPI_Comm_c2f), for an
  // engine that takes one, such as parallel HDF5; -1 on one rank. An integer
  // keeps mpi.h out of the SDK.
  virtual int communicator() const { return -1; }

  // Copies the named fields of the store's halo rows from the ranks that own them.
  virtual void refresh_halo(ParticleStore& store, std::span<const std::string> fields) {
    (void)store;
    (void)fields;
  }
};

}  // namespace talus
