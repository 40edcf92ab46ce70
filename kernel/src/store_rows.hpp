// Whole particles, or some of their fields, as bytes: how particles travel
// between ranks (migration, halo rows) without the mover knowing the fields.
// A packet is field-major: for each field in order, the listed rows' values.
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "talus/particles.hpp"

namespace talus {

// Bytes one particle takes in a packet of these fields.
TALUS_API std::size_t row_bytes(const ParticleStore& store, std::span<const std::string> fields);
// Every field of the store, in its order.
TALUS_API std::vector<std::string> all_fields(const ParticleStore& store);

// Appends the listed rows' values of `fields` to `packet`.
TALUS_API void pack_rows(const ParticleStore& store, std::span<const std::string> fields, std::span<const Index> rows,
               std::vector<std::byte>& packet);
// Writes a packet of `count` rows into rows [first, first + count) of the store.
TALUS_API void unpack_rows(ParticleStore& store, std::span<const std::string> fields, std::span<const std::byte> packet,
                                          std::size_t first, std::size_t count);

}  // namespace talus
