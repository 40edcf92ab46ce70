#include "checkpoint.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "checkpoint_check.hpp"
#include "checkpoint_format.hpp"
#include "crc32.hpp"
#include "ranks.hpp"
#include "talus/blocks.hpp"
#include "talus/error.hpp"
#include "talus/world.hpp"

namespace talus {

namespace checkpoint_format {

std::array<char, header_bytes> header(std::uint64_t payload, std::uint32_t crc) {
  std::array<char, header_bytes> h{};
  std::memcpy(h.data(), magic, sizeof magic);
  h[sizeof magic] = format_version;
  std::memcpy(h.data() + sizeof magic + 1, &payload, sizeof payload);
  std::memcpy(h.data() + sizeof magic + 1 + sizeof payload, &crc, sizeof crc);
  return h;
}

std::uint64_t In::length(const std::string& what, std::size_t element) {
  const auto n = pod<std::uint64_t>(what + " length");
  if (n > left_) fail(what + " claims " + std::to_string(n) + " bytes, only " + std::to_string(left_) + " remain");
  if (n % element)
    fail(what + " holds " + std::to_string(n) + " bytes, not a whole number of " + std::to_string(element) +
         "-byte values");
  return n;
}

void In::rows_into(void* data, std::uint64_t first, std::uint64_t count, std::uint64_t rows, std::size_t element,
                   const std::string& what) {
  const auto n = length(what, element);
  if (n != rows * element)
    fail(what + " holds " + std::to_string(n / element) + " values, expected " + std::to_string(rows));
  skip(first * element, what);
  raw(data, count * element, what);
  skip((rows - first - count) * element, what);
}

void In::raw(void* p, std::size_t n, const std::string& what) {
  if (n > left_)
    fail("truncated: " + what + " needs " + std::to_string(n) + " bytes, only " + std::to_string(left_) + " remain");
  if (n) s_.read(static_cast<char*>(p), static_cast<std::streamsize>(n));
  if (!s_) fail("cannot read " + what + ": " + std::strerror(errno));
  left_ -= n;
}

void In::skip(std::uint64_t n, const std::string& what) {
  if (n == 0) return;
  if (n > left_)
    fail("truncated: " + what + " needs " + std::to_string(n) + " bytes, only " + std::to_string(left_) + " remain");
  s_.seekg(static_cast<std::streamoff>(n), std::ios::cur);
  if (!s_) fail("cannot read " + what + ": " + std::strerror(errno));
  left_ -= n;
}

void write_run(Out& out, const World& world, const RunState& state) {
  out.pod(state.scene_hash);
  out.pod(world.time);
  out.pod(world.step);
  out.pod(world.removed);
  out.pod(state.last_output_time);
  out.vec(state.writer_next_time);
  out.vec(state.writer_next_step);
  out.pod<std::uint64_t>(state.stage_states.size());
  for (const auto& st : state.stage_states) out.text(st);
  out.pod<std::uint64_t>(state.boundary_states.size());
  for (const auto& st : state.boundary_states) out.text(st);
}

void write_store_head(Out& out, std::uint64_t rows, std::uint64_t next_id, std::uint32_t fields) {
  out.pod<std::uint64_t>(rows);
  out.pod<std::uint64_t>(next_id);
  out.pod<std::uint32_t>(fields);
}

void write_column_head(Out& out, const FieldInfo& field, std::uint64_t bytes) {
  out.text(field.name);
  out.pod<std::uint8_t>(static_cast<std::uint8_t>(field.type));
  out.pod<std::uint64_t>(bytes);
}

void write_blocks(Out& out, const World& world) {
  const bool blocks = world.blocks != nullptr;
  out.pod<std::uint8_t>(blocks);
  if (!blocks) return;
  const BlockSet& b = *world.blocks;
  out.vec(b.position);
  out.vec(b.orientation);
  out.vec(b.velocity);
  out.vec(b.angular_velocity);
  out.vec(b.external_force);
  out.vec(b.external_torque);
}

}  // namespace checkpoint_format

namespace {

using namespace checkpoint_format;

void save_store(Out& out, const ParticleStore& store) {
  const auto fields = store.fields();
  write_store_head(out, store.size(), store.next_id(), static_cast<std::uint32_t>(fields.size()));
  for (const auto& f : fields) {
    const auto column = store.bytes(f.name);
    write_column_head(out, f, column.size());
    out.raw(column.data(), column.size());
  }
}

// The checkpoint holds exactly the fields this scene's stages registered, each
// once, with its type; the particle count must fit in the bytes that are left.
// `share` (rank, ranks): this process keeps rows [n rank / ranks, n (rank + 1) / ranks).
void load_store(In& in, ParticleStore& store, const std::string& which, std::pair<int, int> share) {
  const auto n = in.pod<std::uint64_t>(which + " particle count");
  const auto next_id = in.pod<std::uint64_t>(which + " next id");
  const auto fields = store.fields();
  const auto count = in.pod<std::uint32_t>(which + " field count");
  if (count != fields.size())
    in.fail("the " + which + " store has " + std::to_string(count) + " fields, this scene's stages use " +
            std::to_string(fields.size()));
  std::uint64_t per_particle = 0;
  for (const auto& f : fields) per_particle += ParticleStore::element_bytes(f.type);
  if (n > in.left() / std::max<std::uint64_t>(per_particle, 1))
    in.fail("the " + which + " store claims " + std::to_string(n) + " particles, more than the " +
            std::to_string(in.left()) + " bytes left in the file can hold");
  // Resize to n particles (removal keeps the layout; append grows it).
  std::vector<std::uint8_t> drop(store.size(), 1);
  store.remove_if(drop);
  const std::uint64_t first = n * static_cast<std::uint64_t>(share.first) / static_cast<std::uint64_t>(share.second);
  const std::uint64_t last = n * static_cast<std::uint64_t>(share.first + 1) / static_cast<std::uint64_t>(share.second);
  store.append(last - first);
  store.set_next_id(next_id);
  std::vector<std::string> seen;
  for (std::uint32_t k = 0; k < count; ++k) {
    const std::string name = in.text(which + " field name");
    const auto type_byte = in.pod<std::uint8_t>(which + " field '" + name + "' type");
    if (!store.has(name))
      in.fail("it has " + which + " field '" + name + "' that this scene's stages do not use; was it written by another scene?");
    if (std::find(seen.begin(), seen.end(), name) != seen.end()) in.fail(which + " field '" + name + "' appears twice");
    seen.push_back(name);
    const FieldType type = store.info(name).type;
    if (type_byte != static_cast<std::uint8_t>(type)) {
      const std::string saved = type_byte <= static_cast<std::uint8_t>(FieldType::vector_f32)
                                    ? field_type_name(static_cast<FieldType>(type_byte))
                                    : "unknown (" + std::to_string(type_byte) + ")";
      in.fail(which + " field '" + name + "' is " + saved + ", this scene's is " + field_type_name(type));
    }
    const auto column = store.bytes(name);
    const std::size_t element = ParticleStore::element_bytes(type);
    in.rows_into(column.data(), first, column.size() / element, n, element, which + " field '" + name + "'");
  }
}

// Checks the header and the checksum of the whole payload before a byte of
// it is parsed; returns the payload length. On several ranks each reads and
// checksums its part of the payload, and the parts' checksums are combined.
std::uint64_t check_header(std::ifstream& s, const std::string& path, const ranks::Host* ranks) {
  auto fail = [&](const std::string& what) -> void { throw InputError("error: checkpoint " + path + ": " + what); };
  std::error_code ec;
  const std::uint64_t file_size = std::filesystem::file_size(path, ec);
  if (ec) fail("cannot read its size: " + ec.message());
  char head[sizeof magic + 1] = {};
  s.read(head, sizeof head);
  if (!s || std::memcmp(head, magic, sizeof magic) != 0) fail("not a Talus checkpoint");
  if (head[sizeof magic] != format_version)
    fail(std::string("format version ") + head[sizeof magic] + "; this talus reads version " + format_version +
         " only (checkpoints do not carry across versions: rerun the scene from the start)");
  std::uint64_t payload = 0;
  std::uint32_t stored = 0;
  s.read(reinterpret_cast<char*>(&payload), sizeof payload);
  s.read(reinterpret_cast<char*>(&stored), sizeof stored);
  if (!s) fail("truncated: the header is incomplete");
  if (file_size - header_bytes != payload)
    fail("truncated or extended: the header promises " + std::to_string(payload) + " payload bytes, the file holds " +
         std::to_string(file_size - header_bytes));
  std::uint64_t from = 0, to = payload;
  if (ranks) {
    from = payload * static_cast<std::uint64_t>(ranks->rank()) / static_cast<std::uint64_t>(ranks->ranks());
    to = payload * static_cast<std::uint64_t>(ranks->rank() + 1) / static_cast<std::uint64_t>(ranks->ranks());
    s.seekg(static_cast<std::streamoff>(header_bytes + from));
  }
  std::vector<char> chunk(1 << 20);
  std::uint32_t crc = 0;
  for (std::uint64_t left = to - from; left > 0;) {
    const std::size_t n = static_cast<std::size_t>(std::min<std::uint64_t>(left, chunk.size()));
    s.read(chunk.data(), static_cast<std::streamsize>(n));
    if (!s) fail(std::string("cannot read the payload: ") + std::strerror(errno));
    crc = crc32(chunk.data(), n, crc);
    left -= n;
  }
  if (ranks) {
    const std::uint64_t mine[2] = {crc, to - from};
    const std::vector<std::uint64_t> parts = ranks->all_gather(mine);
    crc = 0;
    for (std::size_t r = 0; r < parts.size(); r += 2)
      crc = crc32_combine(crc, static_cast<std::uint32_t>(parts[r]), parts[r + 1]);
  }
  if (crc != stored) {
    char text[96];
    std::snprintf(text, sizeof text, "checksum mismatch (stored %08x, computed %08x): the file is corrupt", stored, crc);
    fail(text);
  }
  s.seekg(static_cast<std::streamoff>(header_bytes));
  return payload;
}

}  // namespace

std::uint64_t text_hash(const std::string& text) {
  std::uint64_t h = 1469598103934665603ull;
  for (unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}

void save_checkpoint(const std::string& path, const World& world, const RunState& state) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream s(tmp, std::ios::binary | std::ios::trunc);
    if (!s) throw RunError("error: cannot write checkpoint " + tmp + ": " + std::strerror(errno));
    s.write(header(0, 0).data(), header_bytes);  // length and checksum filled in below
    Out out(s);
    write_run(out, world, state);
    save_store(out, world.fluid);
    save_store(out, world.boundary);
    write_blocks(out, world);
    s.seekp(0);
    s.write(header(out.size(), out.crc()).data(), header_bytes);
    s.flush();
    if (!s) throw RunError("error: cannot write checkpoint " + tmp + ": " + std::strerror(errno));
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) throw RunError("error: cannot rename " + tmp + " to " + path + ": " + ec.message());
}

RunState load_checkpoint(const std::string& path, World& world, std::uint64_t scene_hash, const ranks::Host* ranks) {
  std::ifstream s(path, std::ios::binary);
  if (!s) throw InputError("error: checkpoint " + path + ": cannot open it: " + std::strerror(errno));
  In in(s, path, check_header(s, path, ranks));
  const std::pair<int, int> share = ranks ? std::pair(ranks->rank(), ranks->ranks()) : std::pair(0, 1);
  RunState state;
  state.scene_hash = in.pod<std::uint64_t>("scene hash");
  if (state.scene_hash != scene_hash)
    in.fail("it was written for a different scene (the scene file changed)");
  world.time = in.pod<double>("time");
  world.step = in.pod<std::uint64_t>("step");
  world.removed = in.pod<std::uint64_t>("removed count");
  state.last_output_time = in.pod<double>("last output time");
  state.writer_next_time = in.vec<double>("output times");
  state.writer_next_step = in.vec<std::uint64_t>("output steps");
  const auto stages = in.pod<std::uint64_t>("stage count");
  if (stages > in.left() / sizeof(std::uint64_t)) in.fail("the stage count " + std::to_string(stages) + " is impossible");
  for (std::uint64_t k = 0; k < stages; ++k) state.stage_states.push_back(in.text("stage " + std::to_string(k + 1) + " state"));
  const auto boundaries = in.pod<std::uint64_t>("boundary model count");
  if (boundaries > in.left() / sizeof(std::uint64_t))
    in.fail("the boundary model count " + std::to_string(boundaries) + " is impossible");
  for (std::uint64_t k = 0; k < boundaries; ++k)
    state.boundary_states.push_back(in.text("boundary model " + std::to_string(k + 1) + " state"));
  load_store(in, world.fluid, "fluid", share);
  load_store(in, world.boundary, "boundary", share);
  const auto blocks = in.pod<std::uint8_t>("block flag");
  if (blocks > 1) in.fail("the block flag is " + std::to_string(blocks) + ", not 0 or 1");
  if ((blocks != 0) != (world.blocks != nullptr))
    in.fail(blocks ? "it has blocks, this scene has none" : "it has no blocks, this scene has some");
  if (blocks) {
    BlockSet& b = *world.blocks;
    auto restore = [&](auto& target, const char* what) {
      auto v = in.vec<typename std::decay_t<decltype(target)>::value_type>(std::string("block ") + what);
      if (v.size() != target.size())
        in.fail("it has " + std::to_string(v.size()) + " block " + what + "s, this scene has " +
                std::to_string(target.size()) + " blocks");
      target = std::move(v);
    };
    restore(b.position, "position");
    restore(b.orientation, "orientation");
    restore(b.velocity, "velocity");
    restore(b.angular_velocity, "angular velocity");
    restore(b.external_force, "external force");
    restore(b.external_torque, "external torque");
  }
  if (in.left() != 0) in.fail(std::to_string(in.left()) + " bytes follow the last block");
  check_restored_state(path, world, state);
  return state;
}

}  // namespace talus
