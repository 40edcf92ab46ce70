// CRC-32 (IEEE 802.3, reflected polynomial 0xEDB88320, as in zlib and PNG):
// the checksum that checkpoints carry over their payload.
#pragma once

#include <cstddef>
#include <cstdint>

#include "talus/config.hpp"

namespace talus {

// Continues `crc` (0 to start) over n bytes; crc32("123456789") = 0xCBF43926.
TALUS_API std::uint32_t crc32(const void* data, std::size_t n, std::uint32_t crc = 0);
// The CRC of A followed by B from the CRCs of each and B's length, without
// the bytes: ranks that each checksum their own part of one file agree on the
// file's checksum.
TALUS_API std::uint32_t crc32_combine(std::uint32_t crc_a, std::uint32_t crc_b, std::uint64_t length_b);

}  // namespace talus
