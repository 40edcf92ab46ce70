// Errors are for people (DESIGN.md principle 7). InputError is bad input
// (exit 2), RunError a run that failed (exit 1). Both carry the full message.
#pragma once

#include <stdexcept>
#include <string>

#include "talus/config.hpp"

namespace talus {

class TALUS_API Error : public std::runtime_error {
 public:
  // A NUL byte (from a string in the input) would end what() early: it reads \u0000.
  explicit Error(const std::string& what);
  explicit Error(const char* what);
  ~Error() override;
};

// Bad scene, mesh, DEM or plugin: message names the file and JSON path.
class TALUS_API InputError : public Error {
 public:
  using Error::Error;
  ~InputError() override;
};

// A simulation that failed while running (non-finite value, I/O failure).
class TALUS_API RunError : public Error {
 public:
  using Error::Error;
  ~RunError() override;
};

}  // namespace talus
