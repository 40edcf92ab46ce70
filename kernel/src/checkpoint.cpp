#include "checkpoint.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "checkpoint_check.hpp"
#include "crc32.hpp"
#include "talus/blocks.hpp"
#include "talus/error.hpp"
#include "talus/world.hpp"

namespace talus {

namespace {

// Header: magic (7 bytes + the format version as a digit), the payload's
// length and its CRC-32. The payload follows. Version 2 added the length and
// the checksum, version 3 the boundary models' state; a file of another
// version is refused, never guessed at.
constexpr char magic[7] = {'T', 'A', 'L', 'U', 'S', 'C', 'K'};
constexpr char format_version = '3';
constexpr std::size_t header_bytes = sizeof magic + 1 + sizeof(std::uint64_t) + sizeof(std::uint32_t);

class Out {
 public:
  explicit Out(std::ofstream& s) : s_(s) {}
  template <class T>
  void pod(const T& v) { raw(&v, sizeof v); }
  void bytes(const void* p, std::size_t n) { pod<std::uint64_t>(n); raw(p, n); }
  void text(const std::string& t) { bytes(t.data(), t.size()); }
  template <class T>
  void vec(const std::vector<T>& v) { bytes(v.data(), v.size() * sizeof(T)); }
  std::uint64_t size() const { return size_; }
  std::uint32_t crc() const { return crc_; }

 private:
  void raw(const void* p, std::size_t n) {
    s_.write(static_cast<const char*>(p), static_cast<std::streamsize>(n));
    crc_ = crc32(p, n, crc_);
    size_ += n;
  }
  std::ofstream& s_;
  std::uint64_t size_ = 0;
  std::uint32_t crc_ = 0;
};

// Reads the payload knowing how many bytes are left, so that no length read
// from the file can make it allocate more than the file holds.
class In {
 public:
  In(std::ifstream& s, const std::string& path, std::uint64_t remaining) : s_(s), path_(path), left_(remaining) {}
  template <class T>
  T pod(const std::string& what) {
    T v{};
    raw(&v, sizeof v, what);
    return v;
  }
  // A length-prefixed block of whole elements of `element` bytes.
  std::uint64_t length(const std::string& what, std::size_t element = 1) {
    const auto n = pod<std::uint64_t>(what + " length");
    if (n > left_) fail(what + " claims " + std::to_string(n) + " bytes, only " + std::to_string(left_) + " remain");
    if (n % element) fail(what + " holds " + std::to_string(n) + " bytes, not a whole number of " + std::to_string(element) + "-byte values");
    return n;
  }
  std::string text(const std::string& what) {
    std::string t(length(what), '\0');
    raw(t.data(), t.size(), what);
    return t;
  }
  template <class T>
  std::vector<T> vec(const std::string& what) {
    std::vector<T> v(length(what, sizeof(T)) / sizeof(T));
    raw(v.data(), v.size() * sizeof(T), what);
    return v;
  }
  template <class T>
  void into(T* data, std::size_t count, const std::string& what) {
    const auto n = length(what, sizeof(T));
    if (n != count * sizeof(T))
      fail(what + " holds " + std::to_string(n / sizeof(T)) + " values, expected " + std::to_string(count));
    raw(data, n, what);
  }
  std::uint64_t left() const { return left_; }
  [[noreturn]] void fail(const std::string& what) const { throw InputError("error: checkpoint " + path_ + ": " + what); }

 private:
  void raw(void* p, std::size_t n, const std::string& what) {
    if (n > left_) fail("truncated: " + what + " needs " + std::to_string(n) + " bytes, only " + std::to_string(left_) + " remain");
    if (n) s_.read(static_cast<char*>(p), static_cast<std::streamsize>(n));
    if (!s_) fail("cannot read " + what + ": " + std::strerror(errno));
    left_ -= n;
  }
  std::ifstream& s_;
  const std::string& path_;
  std::uint64_t left_;
};

void save_store(Out& out, const ParticleStore& store) {
  out.pod<std::uint64_t>(store.size());
  out.pod<std::uint64_t>(store.next_id());
  const auto fields = store.fields();
  out.pod<std::uint32_t>(static_cast<std::uint32_t>(fields.size()));
  for (const auto& f : fields) {
    out.text(f.name);
    out.pod<std::uint8_t>(static_cast<std::uint8_t>(f.type));
    const auto column = store.bytes(f.name);
    out.bytes(column.data(), column.size());
  }
}

// The checkpoint holds exactly the fields this scene's stages registered, each
// once, with its type; the particle count must fit in the bytes that are left.
void load_store(In& in, ParticleStore& store, const std::string& which) {
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
  store.append(n);
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
    if (type_byte != static_cast<std::uint8_t>(type))
      in.fail(which + " field '" + name + "' has type " + std::to_string(type_byte) + ", this scene's has " +
              std::to_string(static_cast<int>(type)));
    const std::string what = which + " field '" + name + "'";
    switch (type) {
      case FieldType::scalar: { auto s = store.scalar(name); in.into(s.data(), s.size(), what); break; }
      case FieldType::vector: { auto s = store.vector(name); in.into(s.data(), s.size(), what); break; }
      case FieldType::integer: { auto s = store.integer(name); in.into(s.data(), s.size(), what); break; }
      case FieldType::id: { auto s = store.ids(); in.into(s.data(), s.size(), what); break; }
    }
  }
}

// Checks the header and the checksum of the whole payload before a byte of
// it is parsed; returns the payload length.
std::uint64_t check_header(std::ifstream& s, const std::string& path) {
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
  std::vector<char> chunk(1 << 20);
  std::uint32_t crc = 0;
  for (std::uint64_t left = payload; left > 0;) {
    const std::size_t n = static_cast<std::size_t>(std::min<std::uint64_t>(left, chunk.size()));
    s.read(chunk.data(), static_cast<std::streamsize>(n));
    if (!s) fail(std::string("cannot read the payload: ") + std::strerror(errno));
    crc = crc32(chunk.data(), n, crc);
    left -= n;
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
    s.write(magic, sizeof magic);
    s.put(format_version);
    const std::uint64_t no_length = 0;
    const std::uint32_t no_crc = 0;
    s.write(reinterpret_cast<const char*>(&no_length), sizeof no_length);  // filled in below
    s.write(reinterpret_cast<const char*>(&no_crc), sizeof no_crc);
    Out out(s);
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
    save_store(out, world.fluid);
    save_store(out, world.boundary);
    const bool blocks = world.blocks != nullptr;
    out.pod<std::uint8_t>(blocks);
    if (blocks) {
      const BlockSet& b = *world.blocks;
      out.vec(b.position);
      out.vec(b.orientation);
      out.vec(b.velocity);
      out.vec(b.angular_velocity);
      out.vec(b.external_force);
      out.vec(b.external_torque);
    }
    const std::uint64_t length = out.size();
    const std::uint32_t crc = out.crc();
    s.seekp(static_cast<std::streamoff>(sizeof magic + 1));
    s.write(reinterpret_cast<const char*>(&length), sizeof length);
    s.write(reinterpret_cast<const char*>(&crc), sizeof crc);
    s.flush();
    if (!s) throw RunError("error: cannot write checkpoint " + tmp + ": " + std::strerror(errno));
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) throw RunError("error: cannot rename " + tmp + " to " + path + ": " + ec.message());
}

RunState load_checkpoint(const std::string& path, World& world, std::uint64_t scene_hash) {
  std::ifstream s(path, std::ios::binary);
  if (!s) throw InputError("error: checkpoint " + path + ": cannot open it: " + std::strerror(errno));
  In in(s, path, check_header(s, path));
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
  load_store(in, world.fluid, "fluid");
  load_store(in, world.boundary, "boundary");
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
