#include "talus/particles.hpp"

#include <algorithm>
#include <stdexcept>
#include <utility>

#include "talus/error.hpp"

namespace talus {

const char* field_type_name(FieldType t) {
  switch (t) {
    case FieldType::scalar: return "scalar";
    case FieldType::vector: return "vector";
    case FieldType::integer: return "integer";
    case FieldType::id: return "id";
    case FieldType::scalar_f32: return "scalar_f32";
    case FieldType::vector_f32: return "vector_f32";
  }
  return "?";
}

namespace {
// The type a field is stored in: its own, or the float form under mixed precision.
FieldType stored_type(const FieldInfo& info, bool mixed) {
  if (!mixed || !info.single_when_mixed) return info.type;
  switch (info.type) {
    case FieldType::scalar: return FieldType::scalar_f32;
    case FieldType::vector: return FieldType::vector_f32;
    case FieldType::scalar_f32:
    case FieldType::vector_f32: return info.type;
    default: throw std::logic_error("field '" + info.name + "': only a scalar or vector field can be kept in float");
  }
}
}  // namespace

ParticleStore::ParticleStore() {
  require({"id", FieldType::id, "", true, true});
  require({"body", FieldType::integer, "", true, true});
  require({"material", FieldType::integer, "", false, true});
  require({"position", FieldType::vector, "m", true, true});
}

void ParticleStore::widen(Field& f) {
  if (auto* column = std::get_if<std::vector<float>>(&f.data)) {
    f.data = std::vector<double>(column->begin(), column->end());
    f.info.type = FieldType::scalar;
  } else if (auto* column = std::get_if<std::vector<Vec3f>>(&f.data)) {
    f.data = std::vector<Vec3>(column->begin(), column->end());
    f.info.type = FieldType::vector;
  }
}

void ParticleStore::set_mixed_precision(bool mixed) {
  if (mixed == mixed_) return;
  for (const auto& f : fields_)
    if (f.info.single_when_mixed)
      throw std::logic_error("ParticleStore::set_mixed_precision: field '" + f.info.name + "' is already registered");
  mixed_ = mixed;
}

void ParticleStore::require(const FieldInfo& info) {
  const FieldType type = stored_type(info, mixed_);
  for (auto& f : fields_)
    if (f.info.name == info.name) {
      if (double_type(f.info.type) != double_type(info.type))
        throw std::logic_error("field '" + info.name + "' requested as " + field_type_name(info.type) +
                               " but registered as " + field_type_name(f.info.type));
      // A field stays in float only while every code that requires it allows
      // that: one that reads it in double widens it (exactly, values kept).
      if (f.info.type != type) widen(f);
      f.info.single_when_mixed = f.info.single_when_mixed && info.single_when_mixed;
      f.info.output = f.info.output || info.output;
      f.info.restart = f.info.restart || info.restart;
      return;
    }
  Field f{info, {}};
  f.info.type = type;
  switch (type) {
    case FieldType::scalar: f.data = std::vector<double>(size_, 0.0); break;
    case FieldType::vector: f.data = std::vector<Vec3>(size_); break;
    case FieldType::integer: f.data = std::vector<std::int32_t>(size_, 0); break;
    case FieldType::id: f.data = std::vector<std::uint64_t>(size_, 0); break;
    case FieldType::scalar_f32: f.data = std::vector<float>(size_, 0.0f); break;
    case FieldType::vector_f32: f.data = std::vector<Vec3f>(size_); break;
  }
  fields_.push_back(std::move(f));
}

bool ParticleStore::has(std::string_view name) const {
  return std::any_of(fields_.begin(), fields_.end(), [&](const Field& f) { return f.info.name == name; });
}

const FieldInfo& ParticleStore::info(std::string_view name) const {
  for (const auto& f : fields_)
    if (f.info.name == name) return f.info;
  throw std::logic_error("no particle field '" + std::string(name) + "'");
}

std::vector<FieldInfo> ParticleStore::fields() const {
  std::vector<FieldInfo> out;
  out.reserve(fields_.size());
  for (const auto& f : fields_) out.push_back(f.info);
  return out;
}

ParticleStore::Field& ParticleStore::field(std::string_view name, FieldType type) {
  return const_cast<Field&>(std::as_const(*this).field(name, type));
}

const ParticleStore::Field& ParticleStore::field(std::string_view name, FieldType type) const {
  for (const auto& f : fields_)
    if (f.info.name == name) {
      if (f.info.type != type)
        throw std::logic_error("field '" + std::string(name) + "' is " + field_type_name(f.info.type) +
                               ", accessed as " + field_type_name(type));
      return f;
    }
  throw std::logic_error("no particle field '" + std::string(name) + "' (a stage must require() it at setup)");
}

std::span<double> ParticleStore::scalar(std::string_view n) { return std::get<0>(field(n, FieldType::scalar).data); }
std::span<const double> ParticleStore::scalar(std::string_view n) const {
  return std::get<0>(field(n, FieldType::scalar).data);
}
std::span<Vec3> ParticleStore::vector(std::string_view n) { return std::get<1>(field(n, FieldType::vector).data); }
std::span<const Vec3> ParticleStore::vector(std::string_view n) const {
  return std::get<1>(field(n, FieldType::vector).data);
}
std::span<std::int32_t> ParticleStore::integer(std::string_view n) {
  return std::get<2>(field(n, FieldType::integer).data);
}
std::span<const std::int32_t> ParticleStore::integer(std::string_view n) const {
  return std::get<2>(field(n, FieldType::integer).data);
}
std::span<std::uint64_t> ParticleStore::ids() { return std::get<3>(field("id", FieldType::id).data); }
std::span<const std::uint64_t> ParticleStore::ids() const { return std::get<3>(field("id", FieldType::id).data); }
std::span<float> ParticleStore::scalar_f32(std::string_view n) {
  return std::get<4>(field(n, FieldType::scalar_f32).data);
}
std::span<const float> ParticleStore::scalar_f32(std::string_view n) const {
  return std::get<4>(field(n, FieldType::scalar_f32).data);
}
std::span<Vec3f> ParticleStore::vector_f32(std::string_view n) {
  return std::get<5>(field(n, FieldType::vector_f32).data);
}
std::span<const Vec3f> ParticleStore::vector_f32(std::string_view n) const {
  return std::get<5>(field(n, FieldType::vector_f32).data);
}

const void* ParticleStore::column_data(std::string_view name, FieldType type) const {
  return std::visit([](const auto& column) -> const void* { return column.data(); }, field(name, type).data);
}
void* ParticleStore::column_data(std::string_view name, FieldType type) {
  return const_cast<void*>(std::as_const(*this).column_data(name, type));
}

std::span<const double> ParticleStore::scalar_in_double(std::string_view name, std::vector<double>& scratch) const {
  if (info(name).type != FieldType::scalar_f32) return scalar(name);
  const auto values = scalar_f32(name);
  scratch.assign(values.begin(), values.end());
  return scratch;
}

std::span<const Vec3> ParticleStore::vector_in_double(std::string_view name, std::vector<Vec3>& scratch) const {
  if (info(name).type != FieldType::vector_f32) return vector(name);
  const auto values = vector_f32(name);
  scratch.assign(values.begin(), values.end());
  return scratch;
}

std::size_t ParticleStore::element_bytes(FieldType type) {
  switch (type) {
    case FieldType::scalar: return sizeof(double);
    case FieldType::vector: return sizeof(Vec3);
    case FieldType::integer: return sizeof(std::int32_t);
    case FieldType::id: return sizeof(std::uint64_t);
    case FieldType::scalar_f32: return sizeof(float);
    case FieldType::vector_f32: return sizeof(Vec3f);
  }
  return 0;
}

std::span<std::byte> ParticleStore::bytes(std::string_view name) {
  const auto b = std::as_const(*this).bytes(name);
  return {const_cast<std::byte*>(b.data()), b.size()};
}

std::span<const std::byte> ParticleStore::bytes(std::string_view name) const {
  for (const auto& f : fields_)
    if (f.info.name == name)
      return std::visit([](const auto& column) { return std::as_bytes(std::span(column)); }, f.data);
  throw std::logic_error("no particle field '" + std::string(name) + "'");
}

void ParticleStore::resize_columns(std::size_t n) {
  for (auto& f : fields_) std::visit([&](auto& column) { column.resize(n); }, f.data);
}

void ParticleStore::require_no_halo(const char* operation) const {
  if (halo_ != 0)
    throw std::logic_error(std::string("ParticleStore::") + operation + ": the store holds halo rows (drop them first)");
}

std::size_t ParticleStore::append(std::size_t n) {
  require_no_halo("append");
  const std::size_t first = size_;
  size_ += n;
  resize_columns(size_);
  auto id = ids();
  for (std::size_t i = first; i < size_; ++i) id[i] = next_id_++;
  return first;
}

void ParticleStore::reserve(std::size_t n) {
  for (auto& f : fields_) std::visit([&](auto& column) { column.reserve(n); }, f.data);
}

std::size_t ParticleStore::append_halo(std::size_t n) {
  const std::size_t first = size_;
  size_ += n;
  halo_ += n;
  resize_columns(size_);
  return first;
}

void ParticleStore::drop_halo() {
  size_ -= halo_;
  halo_ = 0;
  resize_columns(size_);
}

void ParticleStore::reorder(std::span<const Index> order) {
  require_no_halo("reorder");
  if (order.size() != size_) throw std::logic_error("ParticleStore::reorder: permutation size mismatch");
  // In place, cycle by cycle: a bit per particle instead of a copy of the largest column.
  std::vector<std::uint64_t> done((size_ + 63) / 64);
  for (auto& f : fields_) {
    std::visit(
        [&](auto& column) {
          std::fill(done.begin(), done.end(), 0);
          for (std::size_t start = 0; start < size_; ++start) {
            if (done[start / 64] >> (start % 64) & 1) continue;
            const auto first = column[start];
            std::size_t at = start;
            for (std::size_t from = order[at]; from != start; from = order[at]) {
              if (from >= size_ || (done[from / 64] >> (from % 64) & 1))
                throw std::logic_error("ParticleStore::reorder: the order is not a permutation");
              column[at] = column[from];
              done[at / 64] |= std::uint64_t{1} << (at % 64);
              at = from;
            }
            column[at] = first;
            done[at / 64] |= std::uint64_t{1} << (at % 64);
          }
        },
        f.data);
  }
}

std::size_t ParticleStore::remove_if(std::span<const std::uint8_t> flags) {
  require_no_halo("remove_if");
  if (flags.size() != size_) throw std::logic_error("ParticleStore::remove_if: flag size mismatch");
  std::size_t kept = 0;
  for (std::size_t i = 0; i < size_; ++i) kept += flags[i] ? 0 : 1;
  if (kept == size_) return 0;
  for (auto& f : fields_) {
    std::visit(
        [&](auto& column) {
          std::size_t w = 0;
          for (std::size_t i = 0; i < size_; ++i)
            if (!flags[i]) column[w++] = column[i];
          column.resize(kept);
        },
        f.data);
  }
  const std::size_t removed = size_ - kept;
  size_ = kept;
  return removed;
}

}  // namespace talus
