#include "store_rows.hpp"

#include <cstring>
#include <stdexcept>

namespace talus {

std::size_t row_bytes(const ParticleStore& store, std::span<const std::string> fields) {
  std::size_t bytes = 0;
  for (const auto& name : fields) bytes += ParticleStore::element_bytes(store.info(name).type);
  return bytes;
}

std::vector<std::string> all_fields(const ParticleStore& store) {
  std::vector<std::string> names;
  for (const auto& f : store.fields()) names.push_back(f.name);
  return names;
}

void pack_rows(const ParticleStore& store, std::span<const std::string> fields, std::span<const Index> rows,
               std::vector<std::byte>& packet) {
  std::size_t at = packet.size();
  packet.resize(at + rows.size() * row_bytes(store, fields));
  for (const auto& name : fields) {
    const std::size_t element = ParticleStore::element_bytes(store.info(name).type);
    const std::byte* column = store.bytes(name).data();
    for (const Index row : rows) {
      std::memcpy(packet.data() + at, column + static_cast<std::size_t>(row) * element, element);
      at += element;
    }
  }
}

void unpack_rows(ParticleStore& store, std::span<const std::string> fields, std::span<const std::byte> packet,
                 std::size_t first, std::size_t count) {
  if (first + count > store.size() || packet.size() != count * row_bytes(store, fields))
    throw std::logic_error("unpack_rows: the packet does not match the rows it is written to");
  std::size_t at = 0;
  for (const auto& name : fields) {
    const std::size_t element = ParticleStore::element_bytes(store.info(name).type);
    std::byte* column = store.bytes(name).data() + first * element;
    std::memcpy(column, packet.data() + at, count * element);
    at += count * element;
  }
}

}  // namespace talus
