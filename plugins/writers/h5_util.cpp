#include "h5_util.hpp"

#include <exception>
#include <utility>

#include "talus/error.hpp"

namespace talus::writers::h5 {

Handle& Handle::operator=(Handle&& o) noexcept {
  if (this != &o) {
    reset();
    id_ = std::exchange(o.id_, H5I_INVALID_HID);
    closer_ = o.closer_;
  }
  return *this;
}

bool Handle::close() {
  if (id_ < 0) return true;
  const herr_t status = closer_(id_);
  id_ = H5I_INVALID_HID;
  return status >= 0;
}

void Handle::reset() {
  if (id_ >= 0 && closer_) closer_(id_);
  id_ = H5I_INVALID_HID;
}

QuietErrors::QuietErrors() : exceptions_(std::uncaught_exceptions()) {
  H5Eget_auto2(H5E_DEFAULT, &func_, &data_);
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
}

QuietErrors::~QuietErrors() {
  if (std::uncaught_exceptions() == exceptions_) H5Eset_auto2(H5E_DEFAULT, func_, data_);
}

namespace {
herr_t collect(unsigned /*n*/, const H5E_error2_t* err, void* out) {
  auto* text = static_cast<std::vector<std::string>*>(out);
  if (err->desc && *err->desc) text->emplace_back(err->desc);
  return 0;
}
}  // namespace

std::string error_text() {
  std::vector<std::string> descriptions;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_DOWNWARD, collect, &descriptions);
  if (descriptions.empty()) return "HDF5 reported an error without a description";
  for (auto& d : descriptions)
    for (auto& c : d)
      if (c == '\n') c = ' ';
  // The innermost entries name the real cause; a failed system call carries
  // "errno = 28, error message = 'No space left on device'": put that first.
  std::string reason;
  for (const auto& d : descriptions) {
    const auto at = d.find("error message = '");
    if (at == std::string::npos) continue;
    const auto begin = at + 17, end = d.find('\'', begin);
    if (end != std::string::npos) reason = d.substr(begin, end - begin);
  }
  const std::string& inner = descriptions.back();
  const std::string& outer = descriptions.size() > 1 ? descriptions[descriptions.size() - 2] : inner;
  if (!reason.empty()) return reason + " (HDF5: " + outer + ")";
  return descriptions.size() > 1 ? outer + "; " + inner : inner;
}

hid_t check(hid_t id, std::string_view what, const std::string& path) {
  if (id < 0) throw RunError("error: " + std::string(what) + " '" + path + "': " + error_text());
  return id;
}

void check(herr_t status, std::string_view what, const std::string& path) {
  if (status < 0) throw RunError("error: " + std::string(what) + " '" + path + "': " + error_text());
}

Handle create_file(const std::string& path) {
  Handle access(check(H5Pcreate(H5P_FILE_ACCESS), "cannot set up the creation of", path), H5Pclose);
  check(H5Pset_libver_bounds(access, H5F_LIBVER_V18, H5F_LIBVER_LATEST), "cannot set up the creation of", path);
  Handle creation(check(H5Pcreate(H5P_FILE_CREATE), "cannot set up the creation of", path), H5Pclose);
  check(H5Pset_attr_phase_change(creation, 0, 0), "cannot set up the creation of", path);
  return {check(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, creation, access), "cannot create", path), H5Fclose};
}

Handle create_group(hid_t parent, const std::string& name, const std::string& path) {
  return {check(H5Gcreate2(parent, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                "cannot create group " + name + " in", path),
          H5Gclose};
}

Handle open_group(hid_t parent, const std::string& name, const std::string& path) {
  return {check(H5Gopen2(parent, name.c_str(), H5P_DEFAULT), "cannot open group " + name + " in", path), H5Gclose};
}

bool exists(hid_t parent, const std::string& name) { return H5Lexists(parent, name.c_str(), H5P_DEFAULT) > 0; }

void write_dataset(hid_t parent, const std::string& name, hid_t file_type, hid_t mem_type, const void* data,
                   std::uint64_t rows, std::uint64_t cols, const std::string& path, const SharedRows* shared) {
  const int rank = cols > 0 ? 2 : 1;
  const hsize_t dims[2] = {shared ? shared->total : rows, cols};
  const std::string describe = "cannot describe dataset " + name + " in", write = "cannot write dataset " + name + " to";
  Handle space(check(H5Screate_simple(rank, dims, nullptr), describe, path), H5Sclose);
  Handle set(check(H5Dcreate2(parent, name.c_str(), file_type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                   "cannot create dataset " + name + " in", path),
             H5Dclose);
  if (!shared) {
    if (rows > 0) check(H5Dwrite(set, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), write, path);
    return;
  }
  // Every rank takes part in the collective write, one with no rows too.
  if (dims[0] == 0) return;
  const hsize_t start[2] = {shared->first, 0}, count[2] = {rows, cols};
  const hsize_t memory_rows[2] = {rows > 0 ? rows : 1, cols};
  Handle memory(check(H5Screate_simple(rank, memory_rows, nullptr), describe, path), H5Sclose);
  if (rows > 0) {
    check(H5Sselect_hyperslab(space, H5S_SELECT_SET, start, nullptr, count, nullptr), describe, path);
  } else {
    check(H5Sselect_none(space), describe, path);
    check(H5Sselect_none(memory), describe, path);
  }
  const double none = 0.0;  // HDF5 wants a buffer even when it reads nothing from it
  check(H5Dwrite(set, mem_type, memory, space, shared->transfer, rows > 0 ? data : &none), write, path);
}

namespace {
Handle text_type(const std::string& path) {
  Handle t(check(H5Tcopy(H5T_C_S1), "cannot make a string type for", path), H5Tclose);
  check(H5Tset_size(t, H5T_VARIABLE), "cannot make a string type for", path);
  check(H5Tset_cset(t, H5T_CSET_UTF8), "cannot make a string type for", path);
  return t;
}

void write_attribute(hid_t object, const std::string& name, hid_t type, const void* data, hsize_t count, bool scalar,
                     const std::string& path) {
  if (H5Aexists(object, name.c_str()) > 0) H5Adelete(object, name.c_str());
  Handle space(check(scalar ? H5Screate(H5S_SCALAR) : H5Screate_simple(1, &count, nullptr),
                     "cannot describe attribute " + name + " in", path),
               H5Sclose);
  Handle attr(check(H5Acreate2(object, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT),
                    "cannot create attribute " + name + " in", path),
              H5Aclose);
  check(H5Awrite(attr, type, data), "cannot write attribute " + name + " to", path);
}
}  // namespace

void write_strings(hid_t parent, const std::string& name, std::span<const std::string> values,
                   const std::string& path) {
  Handle type = text_type(path);
  std::vector<const char*> pointers;
  pointers.reserve(values.size());
  for (const auto& v : values) pointers.push_back(v.c_str());
  write_dataset(parent, name, type, type, pointers.data(), values.size(), 0, path);
}

// Scalars are written as one-element arrays: the H5Part reader of ParaView
// accepts TimeValue only as a native double with one element.
void set_attribute(hid_t object, const std::string& name, double value, const std::string& path) {
  write_attribute(object, name, H5T_NATIVE_DOUBLE, &value, 1, false, path);
}
void set_attribute(hid_t object, const std::string& name, std::uint64_t value, const std::string& path) {
  write_attribute(object, name, H5T_NATIVE_UINT64, &value, 1, false, path);
}
void set_attribute(hid_t object, const std::string& name, std::int64_t value, const std::string& path) {
  write_attribute(object, name, H5T_NATIVE_INT64, &value, 1, false, path);
}
void set_attribute(hid_t object, const std::string& name, std::span<const double> values, const std::string& path) {
  write_attribute(object, name, H5T_NATIVE_DOUBLE, values.data(), values.size(), false, path);
}
void set_attribute(hid_t object, const std::string& name, std::string_view text, const std::string& path) {
  Handle type = text_type(path);
  const std::string copy(text);
  const char* pointer = copy.c_str();
  write_attribute(object, name, type, &pointer, 1, true, path);
}
void set_attribute(hid_t object, const std::string& name, std::span<const std::string> texts, const std::string& path) {
  Handle type = text_type(path);
  std::vector<const char*> pointers;
  for (const auto& t : texts) pointers.push_back(t.c_str());
  const char* empty = "";
  write_attribute(object, name, type, pointers.empty() ? &empty : pointers.data(),
                  pointers.empty() ? 1 : pointers.size(), false, path);
}

namespace {
bool read_native(hid_t object, const std::string& name, hid_t type, void* out) {
  if (H5Aexists(object, name.c_str()) <= 0) return false;
  Handle attr(H5Aopen(object, name.c_str(), H5P_DEFAULT), H5Aclose);
  if (!attr.valid()) return false;
  Handle space(H5Aget_space(attr), H5Sclose);
  if (H5Sget_simple_extent_npoints(space) != 1) return false;
  return H5Aread(attr, type, out) >= 0;
}
}  // namespace

bool read_attribute(hid_t object, const std::string& name, double& value) {
  return read_native(object, name, H5T_NATIVE_DOUBLE, &value);
}
bool read_attribute(hid_t object, const std::string& name, std::uint64_t& value) {
  return read_native(object, name, H5T_NATIVE_UINT64, &value);
}

}  // namespace talus::writers::h5
