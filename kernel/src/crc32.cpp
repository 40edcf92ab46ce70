#include "crc32.hpp"

#include <array>

namespace talus {

namespace {

constexpr std::uint32_t polynomial = 0xEDB88320u;  // reflected: bit 31 holds x^0, bit 0 x^31

constexpr std::array<std::uint32_t, 256> make_table() {
  std::array<std::uint32_t, 256> t{};
  for (std::uint32_t i = 0; i < 256; ++i) {
    std::uint32_t c = i;
    for (int k = 0; k < 8; ++k) c = (c & 1u) ? polynomial ^ (c >> 1) : c >> 1;
    t[i] = c;
  }
  return t;
}

constexpr auto table = make_table();

// a(x) b(x) mod P over GF(2), both reflected.
std::uint32_t multiply_mod_p(std::uint32_t a, std::uint32_t b) {
  std::uint32_t product = 0;
  for (std::uint32_t term = 0x80000000u; term != 0; term >>= 1) {
    if (a & term) product ^= b;
    b = (b & 1u) ? polynomial ^ (b >> 1) : b >> 1;  // b *= x
  }
  return product;
}

}  // namespace

std::uint32_t crc32(const void* data, std::size_t n, std::uint32_t crc) {
  const auto* p = static_cast<const unsigned char*>(data);
  crc = ~crc;
  for (std::size_t i = 0; i < n; ++i) crc = table[(crc ^ p[i]) & 0xFFu] ^ (crc >> 8);
  return ~crc;
}

// Appending B to A runs A's register on through |B| more bytes: in the
// register's algebra that multiplies it by x^(8|B|) mod P, and B's own CRC adds
// on (the initial and final inversions cancel in the sum).
std::uint32_t crc32_combine(std::uint32_t crc_a, std::uint32_t crc_b, std::uint64_t length_b) {
  std::uint32_t shift = 0x80000000u;  // x^0
  std::uint32_t power = 0x00800000u;  // x^8, one byte
  for (std::uint64_t n = length_b; n != 0; n >>= 1) {
    if (n & 1u) shift = multiply_mod_p(shift, power);
    power = multiply_mod_p(power, power);
  }
  return multiply_mod_p(crc_a, shift) ^ crc_b;
}

}  // namespace talus
