#include "talus/memory.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include "talus/error.hpp"

namespace talus {

namespace {

std::atomic<bool> check_enabled{true};

// The first number in a file (a cgroup limit), 0 if none ("max").
std::uint64_t number_in(const char* path) {
  std::ifstream in(path);
  unsigned long long v = 0;
  if (!(in >> v)) return 0;
  return v;
}

}  // namespace

std::uint64_t available_memory() {
  std::uint64_t available = 0;
  {
    std::ifstream in("/proc/meminfo");
    std::string key;
    unsigned long long kib = 0;
    std::string unit;
    while (in >> key >> kib >> unit)
      if (key == "MemAvailable:") {
        available = static_cast<std::uint64_t>(kib) * 1024;
        break;
      }
  }
  if (available == 0) {
    const long pages = sysconf(_SC_AVPHYS_PAGES), page = sysconf(_SC_PAGESIZE);
    if (pages > 0 && page > 0) available = static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(page);
  }
  // A container's limit ends the process before the machine runs out.
  const std::uint64_t limit_v2 = number_in("/sys/fs/cgroup/memory.max");
  const std::uint64_t used_v2 = number_in("/sys/fs/cgroup/memory.current");
  const std::uint64_t limit_v1 = number_in("/sys/fs/cgroup/memory/memory.limit_in_bytes");
  const std::uint64_t used_v1 = number_in("/sys/fs/cgroup/memory/memory.usage_in_bytes");
  for (auto [limit, used] : {std::pair{limit_v2, used_v2}, std::pair{limit_v1, used_v1}})
    if (limit > 0 && limit < (1ull << 62)) available = std::min(available, limit > used ? limit - used : 0);
  // An address-space limit (ulimit -v) makes allocation fail past it, less what is mapped already.
  rlimit as{};
  if (getrlimit(RLIMIT_AS, &as) == 0 && as.rlim_cur != RLIM_INFINITY) {
    const std::uint64_t mapped = number_in("/proc/self/statm") * static_cast<std::uint64_t>(sysconf(_SC_PAGESIZE));
    const std::uint64_t limit = as.rlim_cur;
    available = std::min(available, limit > mapped ? limit - mapped : 0);
  }
  return available;
}

void set_memory_check(bool enabled) { check_enabled.store(enabled); }
bool memory_check_enabled() { return check_enabled.load(); }

std::string memory_text(double bytes) {
  if (!std::isfinite(bytes)) return "more than can be counted";
  const char* units[] = {"bytes", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  int u = 0;
  while (bytes >= 1024.0 && u < 6) {
    bytes /= 1024.0;
    ++u;
  }
  char text[64];
  if (u == 6 && bytes >= 1024.0)
    std::snprintf(text, sizeof text, "%.3g EiB", bytes);
  else
    std::snprintf(text, sizeof text, u == 0 ? "%.0f %s" : "%.3g %s", bytes, units[u]);
  return text;
}

void require_memory(double bytes, const std::string& where, const std::string& what) {
  if (!memory_check_enabled()) return;
  const double available = static_cast<double>(available_memory());
  if (bytes <= available) return;  // a NaN estimate is refused too
  throw InputError("error: " + where + ": " + what + " needs about " + memory_text(bytes) +
                   " of memory; this machine has " + memory_text(available) +
                   " available.\n       Coarsen it, or run with --allow-large to try anyway.");
}

}  // namespace talus
