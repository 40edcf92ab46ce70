// CRC-32 (IEEE 802.3, reflected polynomial 0xEDB88320, as in zlib and PNG):
// the checksum that checkpoints carry over their payload.
#pragma once

#include <cstddef>
#include <cstdint>

#include "talus/config.hpp"

namespace talus {

// Continues `crc` (0 to start) over n bytes; crc32("123456789") = 0xCBF43926.
TALUS_API std::uint32_t crc32(const void* data, std::size_t n, std::uint32_t crc = 0);

}  // namespace talus
