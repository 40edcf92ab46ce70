// The checkpoint file's layout, shared by the serial writer and reader
// (checkpoint.cpp) and the one the MPI ranks write together
// (checkpoint_ranks.cpp): the header, the byte streams with their running
// CRC, and each section.
//
// Header: magic (7 bytes + the format version as a digit), the payload's
// length and its CRC-32. The payload follows. Version 2 added the length and
// the checksum, version 3 the boundary models' state; a file of another
// version is refused, never guessed at.
#pragma once

#include <array>
#include <cstdint>
#include <cstring>
#include <istream>
#include <ostream>
#include <string>
#include <vector>

#include "checkpoint.hpp"
#include "crc32.hpp"
#include "talus/error.hpp"
#include "talus/particles.hpp"

namespace talus::checkpoint_format {

constexpr char magic[7] = {'T', 'A', 'L', 'U', 'S', 'C', 'K'};
constexpr char format_version = '3';
constexpr std::size_t header_bytes = sizeof magic + 1 + sizeof(std::uint64_t) + sizeof(std::uint32_t);

std::array<char, header_bytes> header(std::uint64_t payload, std::uint32_t crc);

// Writes the payload, keeping its length and CRC.
class Out {
 public:
  explicit Out(std::ostream& s) : s_(s) {}
  template <class T>
  void pod(const T& v) { raw(&v, sizeof v); }
  void bytes(const void* p, std::size_t n) { pod<std::uint64_t>(n); raw(p, n); }
  void text(const std::string& t) { bytes(t.data(), t.size()); }
  template <class T>
  void vec(const std::vector<T>& v) { bytes(v.data(), v.size() * sizeof(T)); }
  void raw(const void* p, std::size_t n) {
    s_.write(static_cast<const char*>(p), static_cast<std::streamsize>(n));
    crc_ = crc32(p, n, crc_);
    size_ += n;
  }
  std::uint64_t size() const { return size_; }
  std::uint32_t crc() const { return crc_; }

 private:
  std::ostream& s_;
  std::uint64_t size_ = 0;
  std::uint32_t crc_ = 0;
};

// Reads the payload knowing how many bytes are left, so that no length read
// from the file can make it allocate more than the file holds.
class In {
 public:
  In(std::istream& s, const std::string& path, std::uint64_t remaining) : s_(s), path_(path), left_(remaining) {}
  template <class T>
  T pod(const std::string& what) {
    T v{};
    raw(&v, sizeof v, what);
    return v;
  }
  // A length-prefixed block of whole elements of `element` bytes.
  std::uint64_t length(const std::string& what, std::size_t element = 1);
  std::string text(const std::string& what) {
    std::string t(length(what), '\0');
    raw(t.data(), t.size(), what);
    return t;
  }
  template <class T>
  std::vector<T> vec(const std::string& what) {
    std::vector<T> v(length(what, sizeof(T)) / sizeof(T));
    raw(v.data(), v.size() * sizeof(T), what);
    return v;
  }
  // Rows [first, first + count) of a column of `rows` rows of `element`
  // bytes into `data`; the column's other rows are skipped.
  void rows_into(void* data, std::uint64_t first, std::uint64_t count, std::uint64_t rows, std::size_t element,
                 const std::string& what);
  std::uint64_t left() const { return left_; }
  [[noreturn]] void fail(const std::string& what) const { throw InputError("error: checkpoint " + path_ + ": " + what); }

 private:
  void raw(void* p, std::size_t n, const std::string& what);
  void skip(std::uint64_t n, const std::string& what);
  std::istream& s_;
  const std::string& path_;
  std::uint64_t left_;
};

// The sections in file order. The run: the clock, the output schedule, the
// stages' and boundary models' states.
void write_run(Out& out, const World& world, const RunState& state);
// A store: its row count, next id and field count, then per field a column
// head followed by the column's bytes (every row of the field in turn).
void write_store_head(Out& out, std::uint64_t rows, std::uint64_t next_id, std::uint32_t fields);
void write_column_head(Out& out, const FieldInfo& field, std::uint64_t bytes);
void write_blocks(Out& out, const World& world);

}  // namespace talus::checkpoint_format
