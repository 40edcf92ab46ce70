// Thin RAII layer over the HDF5 C API: handles that close themselves, an
// error guard that silences HDF5's own stack printing and turns a failed call
// into a RunError naming the file and HDF5's innermost reason (which carries
// the system's errno text, e.g. "No space left on device").
#pragma once

#include <hdf5.h>

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace talus::writers::h5 {

// Owns one hid_t and closes it with the right H5?close.
class Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  Handle() = default;
  Handle(hid_t id, Closer closer) : id_(id), closer_(closer) {}
  Handle(Handle&& o) noexcept : id_(o.id_), closer_(o.closer_) { o.id_ = H5I_INVALID_HID; }
  Handle& operator=(Handle&& o) noexcept;
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  ~Handle() { reset(); }

  hid_t get() const { return id_; }
  operator hid_t() const { return id_; }
  bool valid() const { return id_ >= 0; }
  // Closes now and reports whether the close succeeded (a file close flushes).
  bool close();
  void reset();

 private:
  hid_t id_ = H5I_INVALID_HID;
  Closer closer_ = nullptr;
};

// While alive, HDF5 prints nothing on errors; restores the previous handler
// on a normal exit. When it is left by an exception the handler stays off:
// HDF5 1.10 keeps a file whose creation failed (disk full) in its open-file
// list, and at process exit its shutdown would print "infinite loop closing
// library" and a page of codes after our clear RunError.
class QuietErrors {
 public:
  QuietErrors();
  ~QuietErrors();
  QuietErrors(const QuietErrors&) = delete;
  QuietErrors& operator=(const QuietErrors&) = delete;

 private:
  H5E_auto2_t func_ = nullptr;
  void* data_ = nullptr;
  int exceptions_ = 0;
};

// The descriptions on the current HDF5 error stack, innermost last, joined.
std::string error_text();

// Throws RunError "error: WHAT 'PATH': <system reason> (HDF5: ...)" when id < 0.
hid_t check(hid_t id, std::string_view what, const std::string& path);
void check(herr_t status, std::string_view what, const std::string& path);

// Writing helpers; `path` only names the file in error messages.

// A new file (replacing one there), in the HDF5 1.8 format so that attributes
// go to dense storage and may pass 64 KiB (a scene of thousands of blocks
// names them all in one attribute).
Handle create_file(const std::string& path);
Handle create_group(hid_t parent, const std::string& name, const std::string& path);
Handle open_group(hid_t parent, const std::string& name, const std::string& path);
bool exists(hid_t parent, const std::string& name);

// Where one MPI rank's rows go in a dataset the ranks write together: from
// row `first` of `total`, in a transfer every rank takes part in (h5_ranks.hpp).
struct SharedRows {
  std::uint64_t total = 0;
  std::uint64_t first = 0;
  hid_t transfer = H5P_DEFAULT;
};

// A 1-D (rows) or 2-D (rows x cols) dataset of `file_type` from native data;
// with `shared`, the `rows` given are this rank's part of it.
void write_dataset(hid_t parent, const std::string& name, hid_t file_type, hid_t mem_type, const void* data,
                   std::uint64_t rows, std::uint64_t cols, const std::string& path, const SharedRows* shared = nullptr);
void write_strings(hid_t parent, const std::string& name, std::span<const std::string> values, const std::string& path);

void set_attribute(hid_t object, const std::string& name, double value, const std::string& path);
void set_attribute(hid_t object, const std::string& name, std::uint64_t value, const std::string& path);
void set_attribute(hid_t object, const std::string& name, std::int64_t value, const std::string& path);
void set_attribute(hid_t object, const std::string& name, std::span<const double> values, const std::string& path);
void set_attribute(hid_t object, const std::string& name, std::string_view text, const std::string& path);
void set_attribute(hid_t object, const std::string& name, std::span<const std::string> texts, const std::string& path);

// Reading helpers (resume after a restart, tests).
bool read_attribute(hid_t object, const std::string& name, double& value);
bool read_attribute(hid_t object, const std::string& name, std::uint64_t& value);

}  // namespace talus::writers::h5
