#include "checkpoint.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "talus/blocks.hpp"
#include "talus/error.hpp"
#include "talus/world.hpp"

namespace talus {

namespace {

constexpr char magic[8] = {'T', 'A', 'L', 'U', 'S', 'C', 'K', '1'};

class Out {
 public:
  explicit Out(std::ofstream& s) : s_(s) {}
  template <class T>
  void pod(const T& v) { s_.write(reinterpret_cast<const char*>(&v), sizeof v); }
  void bytes(const void* p, std::size_t n) { pod<std::uint64_t>(n); s_.write(static_cast<const char*>(p), n); }
  void text(const std::string& t) { bytes(t.data(), t.size()); }
  template <class T>
  void vec(const std::vector<T>& v) { bytes(v.data(), v.size() * sizeof(T)); }

 private:
  std::ofstream& s_;
};

class In {
 public:
  In(std::ifstream& s, const std::string& path) : s_(s), path_(path) {}
  template <class T>
  T pod() {
    T v{};
    s_.read(reinterpret_cast<char*>(&v), sizeof v);
    check();
    return v;
  }
  std::string text() {
    const auto n = pod<std::uint64_t>();
    if (n > (1ull << 40)) corrupt();
    std::string t(n, '\0');
    s_.read(t.data(), static_cast<std::streamsize>(n));
    check();
    return t;
  }
  template <class T>
  void into(T* data, std::size_t count) {
    const auto n = pod<std::uint64_t>();
    if (n != count * sizeof(T)) corrupt();
    s_.read(reinterpret_cast<char*>(data), static_cast<std::streamsize>(n));
    check();
  }
  template <class T>
  std::vector<T> vec() {
    const std::string t = text();
    if (t.size() % sizeof(T)) corrupt();
    std::vector<T> v(t.size() / sizeof(T));
    if (!v.empty()) std::memcpy(v.data(), t.data(), t.size());  // an empty vector's data() may be null
    return v;
  }
  [[noreturn]] void corrupt() const { throw InputError("error: " + path_ + ": checkpoint is truncated or corrupt"); }

 private:
  void check() const {
    if (!s_) corrupt();
  }
  std::ifstream& s_;
  std::string path_;
};

void save_store(Out& out, const ParticleStore& store) {
  out.pod<std::uint64_t>(store.size());
  out.pod<std::uint64_t>(store.next_id());
  const auto fields = store.fields();
  out.pod<std::uint32_t>(static_cast<std::uint32_t>(fields.size()));
  for (const auto& f : fields) {
    out.text(f.name);
    out.pod<std::uint8_t>(static_cast<std::uint8_t>(f.type));
    switch (f.type) {
      case FieldType::scalar: { auto s = store.scalar(f.name); out.bytes(s.data(), s.size_bytes()); break; }
      case FieldType::vector: { auto s = store.vector(f.name); out.bytes(s.data(), s.size_bytes()); break; }
      case FieldType::integer: { auto s = store.integer(f.name); out.bytes(s.data(), s.size_bytes()); break; }
      case FieldType::id: { auto s = store.ids(); out.bytes(s.data(), s.size_bytes()); break; }
    }
  }
}

void load_store(In& in, ParticleStore& store, const char* which) {
  const auto n = in.pod<std::uint64_t>();
  const auto next_id = in.pod<std::uint64_t>();
  // Resize to n particles (removal keeps the layout; append grows it).
  std::vector<std::uint8_t> drop(store.size(), 1);
  store.remove_if(drop);
  store.append(n);
  store.set_next_id(next_id);
  const auto count = in.pod<std::uint32_t>();
  for (std::uint32_t k = 0; k < count; ++k) {
    const std::string name = in.text();
    const auto type = static_cast<FieldType>(in.pod<std::uint8_t>());
    if (!store.has(name))
      throw InputError(std::string("error: checkpoint has ") + which + " field '" + name +
                       "' that this scene's stages do not use; was it written by another scene or version?");
    switch (type) {
      case FieldType::scalar: { auto s = store.scalar(name); in.into(s.data(), s.size()); break; }
      case FieldType::vector: { auto s = store.vector(name); in.into(s.data(), s.size()); break; }
      case FieldType::integer: { auto s = store.integer(name); in.into(s.data(), s.size()); break; }
      case FieldType::id: { auto s = store.ids(); in.into(s.data(), s.size()); break; }
    }
  }
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
    Out out(s);
    s.write(magic, sizeof magic);
    out.pod(state.scene_hash);
    out.pod(world.time);
    out.pod(world.step);
    out.pod(world.removed);
    out.pod(state.last_output_time);
    out.vec(state.writer_next_time);
    out.vec(state.writer_next_step);
    out.pod<std::uint64_t>(state.stage_states.size());
    for (const auto& st : state.stage_states) out.text(st);
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
    s.flush();
    if (!s) throw RunError("error: cannot write checkpoint " + tmp + ": " + std::strerror(errno));
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) throw RunError("error: cannot rename " + tmp + " to " + path + ": " + ec.message());
}

RunState load_checkpoint(const std::string& path, World& world, std::uint64_t scene_hash) {
  std::ifstream s(path, std::ios::binary);
  if (!s) throw InputError("error: " + path + ": cannot open checkpoint: " + std::strerror(errno));
  char head[sizeof magic];
  s.read(head, sizeof head);
  if (!s || std::memcmp(head, magic, sizeof magic) != 0) throw InputError("error: " + path + ": not a Talus checkpoint");
  In in(s, path);
  RunState state;
  state.scene_hash = in.pod<std::uint64_t>();
  if (state.scene_hash != scene_hash)
    throw InputError("error: " + path + ": checkpoint was written for a different scene (the scene file changed)");
  world.time = in.pod<double>();
  world.step = in.pod<std::uint64_t>();
  world.removed = in.pod<std::uint64_t>();
  state.last_output_time = in.pod<double>();
  state.writer_next_time = in.vec<double>();
  state.writer_next_step = in.vec<std::uint64_t>();
  const auto stages = in.pod<std::uint64_t>();
  for (std::uint64_t k = 0; k < stages; ++k) state.stage_states.push_back(in.text());
  load_store(in, world.fluid, "fluid");
  load_store(in, world.boundary, "boundary");
  const bool blocks = in.pod<std::uint8_t>() != 0;
  if (blocks != (world.blocks != nullptr)) in.corrupt();
  if (blocks) {
    BlockSet& b = *world.blocks;
    auto restore = [&](auto& target) {
      auto v = in.vec<typename std::decay_t<decltype(target)>::value_type>();
      if (v.size() != target.size()) in.corrupt();
      target = std::move(v);
    };
    restore(b.position);
    restore(b.orientation);
    restore(b.velocity);
    restore(b.angular_velocity);
    restore(b.external_force);
    restore(b.external_torque);
  }
  return state;
}

}  // namespace talus
