// Up-front memory checks: a scene or input file whose size would need more
// memory than the machine can give is refused (InputError, exit 2) before
// anything is allocated, rather than ending in the OOM killer or bad_alloc.
// `talus run --allow-large` turns the refusal off.
#pragma once

#include <cstdint>
#include <string>

#include "talus/config.hpp"

namespace talus {

// Bytes this process can allocate now: MemAvailable from /proc/meminfo (or
// free pages from sysconf), capped by the cgroup's memory limit and by the
// address-space limit (ulimit -v, less what the process already maps).
TALUS_API std::uint64_t available_memory();

// Whether require_memory refuses (default true; --allow-large sets false).
TALUS_API void set_memory_check(bool enabled);
TALUS_API bool memory_check_enabled();

// Throws InputError "error: WHERE: WHAT needs about N GiB of memory; this
// machine has M GiB available ..." if `bytes` exceeds available_memory() and
// the check is on. `where` is the file (and JSON pointer) that drives the size.
TALUS_API void require_memory(double bytes, const std::string& where, const std::string& what);

// "1.5 GiB", "320 MiB": a byte count for messages.
TALUS_API std::string memory_text(double bytes);

}  // namespace talus
