// Flat binary archives for the opaque checkpoint state of stages and boundary
// models (Stage::save_state, Boundary::save_state; same build, same machine:
// checkpoints are not an exchange format). `what` names the state in the
// error a truncated checkpoint raises.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

#include "talus/error.hpp"

namespace talus {

struct StateWriter {
  std::string out;
  template <class T>
  void value(const T& v) { out.append(reinterpret_cast<const char*>(&v), sizeof v); }
  template <class T>
  void vector(const std::vector<T>& v) {
    value<std::uint64_t>(v.size());
    if (!v.empty()) out.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
  }
  void bytes(std::string_view s) {
    value<std::uint64_t>(s.size());
    out.append(s);
  }
};

struct StateReader {
  std::string_view in;
  const char* what = "a stage's state";

  [[noreturn]] void truncated() const { throw InputError(std::string("error: checkpoint: ") + what + " is truncated"); }
  template <class T>
  void value(T& v) {
    if (in.size() < sizeof v) truncated();
    std::memcpy(&v, in.data(), sizeof v);
    in.remove_prefix(sizeof v);
  }
  template <class T>
  void vector(std::vector<T>& v) {
    std::uint64_t n = 0;
    value(n);
    if (n > in.size() / sizeof(T)) truncated();
    v.resize(n);
    if (n > 0) std::memcpy(v.data(), in.data(), n * sizeof(T));
    in.remove_prefix(n * sizeof(T));
  }
  void bytes(std::string& s) {
    std::uint64_t n = 0;
    value(n);
    if (n > in.size()) truncated();
    s.assign(in.data(), n);
    in.remove_prefix(n);
  }
  void finish() const {
    if (!in.empty()) throw InputError(std::string("error: checkpoint: ") + what + " has trailing bytes");
  }
};

}  // namespace talus
