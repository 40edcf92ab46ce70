// One file that several MPI ranks write together through MPI-IO: each rank
// writes its own bytes at offsets the caller worked out. For the checkpoints
// (checkpoint_ranks.cpp), whose format is the serial one.
#pragma once

#include <mpi.h>

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

#include "ranks.hpp"

namespace talus::mpi {

class SharedFile final : public ranks::SharedFile {
 public:
  // Creates (or empties) `path` on every rank of `comm`; collective.
  SharedFile(MPI_Comm comm, std::string path);
  ~SharedFile() override;

  void write_alone(std::uint64_t offset, std::span<const std::byte> bytes) override;
  void write_together(std::uint64_t offset, std::span<const std::byte> bytes) override;
  void close() override;

 private:
  [[noreturn]] void fail(const char* what, int code) const;
  MPI_Comm comm_;
  std::string path_;
  MPI_File file_ = MPI_FILE_NULL;
};

}  // namespace talus::mpi
