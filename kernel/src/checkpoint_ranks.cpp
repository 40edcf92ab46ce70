// A checkpoint the MPI ranks write together, in the serial format: the
// payload is a row of pieces, the sections rank 0 writes alone and the
// columns of every field, to which each rank adds its owned rows in rank
// order. Every rank checksums what it writes; the checksums are combined
// (crc32_combine) into the header's, so no rank reads another's bytes.
#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "checkpoint.hpp"
#include "checkpoint_format.hpp"
#include "crc32.hpp"
#include "ranks.hpp"
#include "talus/world.hpp"

namespace talus {

using namespace checkpoint_format;

void save_checkpoint_on_ranks(const std::string& path, const World& world, const RunState& state,
                              const ranks::Host& ranks) {
  const bool root = ranks.rank() == 0;
  struct Piece {
    std::string alone;                // a section: rank 0's bytes (empty elsewhere)
    std::span<const std::byte> rows;  // a column: this rank's rows
    bool column = false;
  };
  std::vector<Piece> pieces;
  auto section = [&](const auto& write) {
    std::ostringstream bytes;
    Out out(bytes);
    write(out);
    pieces.push_back({root ? bytes.str() : std::string(), {}, false});
  };
  section([&](Out& out) { write_run(out, world, state); });
  for (const ParticleStore* store : {&world.fluid, &world.boundary}) {
    const auto fields = store->fields();
    const std::uint64_t owned = store->owned_size();
    const std::uint64_t rows = ranks.sum(owned);
    std::uint64_t next_id = 0;
    const std::uint64_t mine = store->next_id();
    for (const std::uint64_t id : ranks.all_gather({&mine, 1})) next_id = std::max(next_id, id);
    section([&](Out& out) { write_store_head(out, rows, next_id, static_cast<std::uint32_t>(fields.size())); });
    for (const auto& f : fields) {
      const std::size_t element = ParticleStore::element_bytes(f.type);
      section([&](Out& out) { write_column_head(out, f, rows * element); });
      pieces.push_back({{}, store->bytes(f.name).first(owned * element), true});
    }
  }
  section([&](Out& out) { write_blocks(out, world); });

  // Every rank learns every piece's length on every rank, and so where its own go.
  std::vector<std::uint64_t> mine;
  for (const Piece& p : pieces) {
    const auto bytes = p.column ? p.rows : std::as_bytes(std::span(p.alone));
    mine.push_back(crc32(bytes.data(), bytes.size()));
    mine.push_back(bytes.size());
  }
  const std::vector<std::uint64_t> all = ranks.all_gather(mine);
  auto crc_of = [&](int r, std::size_t k) { return static_cast<std::uint32_t>(all[(r * pieces.size() + k) * 2]); };
  auto length_of = [&](int r, std::size_t k) { return all[(r * pieces.size() + k) * 2 + 1]; };

  const std::string tmp = path + ".tmp";
  const auto file = ranks.create_shared_file(tmp);
  std::uint64_t at = header_bytes;
  std::uint32_t crc = 0;
  for (std::size_t k = 0; k < pieces.size(); ++k) {
    std::uint64_t mine_at = at;
    for (int r = 0; r < ranks.rank(); ++r) mine_at += length_of(r, k);
    if (pieces[k].column) file->write_together(mine_at, pieces[k].rows);
    else if (root) file->write_alone(at, std::as_bytes(std::span(pieces[k].alone)));
    for (int r = 0; r < ranks.ranks(); ++r) {
      crc = crc32_combine(crc, crc_of(r, k), length_of(r, k));
      at += length_of(r, k);
    }
  }
  const auto head = header(at - header_bytes, crc);
  if (root) file->write_alone(0, std::as_bytes(std::span(head)));
  file->close();
  if (!root) return;
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) throw RunError("error: cannot rename " + tmp + " to " + path + ": " + ec.message());
}

}  // namespace talus
