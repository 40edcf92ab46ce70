#include "shared_file.hpp"

#include <algorithm>
#include <string>
#include <utility>

#include "talus/error.hpp"

namespace talus::mpi {

namespace {
// MPI counts are ints: larger writes go in pieces of at most this many bytes.
constexpr std::uint64_t piece_bytes = std::uint64_t{1} << 30;
}  // namespace

SharedFile::SharedFile(MPI_Comm comm, std::string path) : comm_(comm), path_(std::move(path)) {
  const int code = MPI_File_open(comm_, path_.c_str(), MPI_MODE_CREATE | MPI_MODE_WRONLY, MPI_INFO_NULL, &file_);
  if (code != MPI_SUCCESS) fail("cannot create", code);
  if (const int c = MPI_File_set_size(file_, 0); c != MPI_SUCCESS) fail("cannot empty", c);
}

SharedFile::~SharedFile() {
  if (file_ != MPI_FILE_NULL) MPI_File_close(&file_);
}

void SharedFile::fail(const char* what, int code) const {
  char text[MPI_MAX_ERROR_STRING];
  int length = 0;
  MPI_Error_string(code, text, &length);
  throw RunError("error: " + std::string(what) + " checkpoint " + path_ + ": " + std::string(text, length));
}

void SharedFile::write_alone(std::uint64_t offset, std::span<const std::byte> bytes) {
  for (std::uint64_t done = 0; done < bytes.size();) {
    const auto n = static_cast<int>(std::min<std::uint64_t>(bytes.size() - done, piece_bytes));
    MPI_Status status;
    if (const int c = MPI_File_write_at(file_, static_cast<MPI_Offset>(offset + done), bytes.data() + done, n,
                                        MPI_BYTE, &status);
        c != MPI_SUCCESS)
      fail("cannot write", c);
    done += static_cast<std::uint64_t>(n);
  }
}

void SharedFile::write_together(std::uint64_t offset, std::span<const std::byte> bytes) {
  // Every rank makes the same number of collective calls, one with nothing left too.
  std::uint64_t pieces = (bytes.size() + piece_bytes - 1) / piece_bytes, most = 0;
  MPI_Allreduce(&pieces, &most, 1, MPI_UINT64_T, MPI_MAX, comm_);
  for (std::uint64_t k = 0; k < most; ++k) {
    const std::uint64_t done = std::min<std::uint64_t>(k * piece_bytes, bytes.size());
    const auto n = static_cast<int>(std::min<std::uint64_t>(bytes.size() - done, piece_bytes));
    MPI_Status status;
    if (const int c = MPI_File_write_at_all(file_, static_cast<MPI_Offset>(offset + done), bytes.data() + done, n,
                                            MPI_BYTE, &status);
        c != MPI_SUCCESS)
      fail("cannot write", c);
  }
}

void SharedFile::close() {
  if (const int c = MPI_File_close(&file_); c != MPI_SUCCESS) fail("cannot close", c);
}

}  // namespace talus::mpi
