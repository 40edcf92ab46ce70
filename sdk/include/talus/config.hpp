// Basic configuration shared by the host and every plugin: the real type, the
// export macro and the SDK ABI version the descriptor check compares.
#pragma once

#include <cstdint>

#define TALUS_API __attribute__((visibility("default")))

// For functions of a pair loop body (SPH pair terms, kernel lookups): the
// compiler otherwise keeps one call per term per pair at -O2/-O3.
#define TALUS_PAIR_INLINE [[gnu::always_inline]] inline

namespace talus {

using Real = double;  // SI units, double precision (DESIGN.md principle 6)
using Index = std::uint32_t;

// Bump whenever a public SDK type changes layout or meaning. A plugin built
// for another value is refused at load time.
inline constexpr int sdk_abi_version = 3;

}  // namespace talus
