// Structure-of-arrays particle store (DESIGN.md principle 2). Fields are
// registered by name on demand: a plugin asks for "mu_eff" and only then is it
// allocated. Every field is one contiguous array (a Vec3 field is an array of
// Vec3), so a pair loop touches only the arrays it needs.
//
// Mixed precision (set_mixed_precision, before any field is required): a
// field whose metadata allows it (FieldInfo::single_when_mixed) is stored in
// float, as scalar_f32 or vector_f32, and read and written through
// scalar_f32() / vector_f32() or column<T>(); scalar() and vector() refuse it.
// A field is kept in float only if every require() of it allows that: a
// require() that does not widens it to double.
// Positions, ids, bodies and materials always keep their types.
//
// Always present: "id" (global id, survives re-sorting, removal and moving to
// another rank), "body" (index of the scene body), "material" (index of the
// material, or -1), "position".
//
// On a run spread over MPI ranks (parallel.hpp) the rank's own particles come
// first, [0, owned_size()); behind them are halo rows, copies of other ranks'
// particles that this rank's pair loops read. Appending, re-sorting and
// removing work on a store without halo rows only (the host drops them first).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <variant>
#include <vector>

#include "talus/config.hpp"
#include "talus/vec3.hpp"

namespace talus {

enum class FieldType { scalar, vector, integer, id, scalar_f32, vector_f32 };

// The type's name, as errors and checkpoints print it.
TALUS_API const char* field_type_name(FieldType type);

// The type a field of this type has in double (scalar for scalar_f32, vector
// for vector_f32, the type itself otherwise): what the field is, whichever
// precision it is stored in.
constexpr FieldType double_type(FieldType type) {
  return type == FieldType::scalar_f32 ? FieldType::scalar : type == FieldType::vector_f32 ? FieldType::vector : type;
}
// Whether a field of this type is kept in float.
constexpr bool is_single(FieldType type) { return double_type(type) != type; }

// What the host and the writers need to know about a field.
struct FieldInfo {
  std::string name;
  FieldType type = FieldType::scalar;
  std::string unit;       // SI unit text
  bool output = true;     // written by writers that write "all" fields
  bool restart = true;    // saved in checkpoints (state, not derived)
  // A scalar or vector field that may be kept in float when the store is in
  // mixed precision; its type in the store then becomes scalar_f32 or vector_f32.
  bool single_when_mixed = false;
};

class TALUS_API ParticleStore {
 public:
  ParticleStore();

  std::size_t size() const { return size_; }
  std::size_t owned_size() const { return size_ - halo_; }
  std::size_t halo_size() const { return halo_; }

  // Bytes of one particle's value of a field of this type.
  static std::size_t element_bytes(FieldType type);

  // Whether fields that allow it are stored in float. Set it before the first
  // require() of such a field (the host does, from the scene).
  void set_mixed_precision(bool mixed);
  bool mixed_precision() const { return mixed_; }

  // Registers a field if it does not exist yet (idempotent; the type must
  // match an existing registration) and returns nothing: use the accessors.
  // info(name).type is the type the field is stored in.
  void require(const FieldInfo& info);
  bool has(std::string_view name) const;
  const FieldInfo& info(std::string_view name) const;
  std::vector<FieldInfo> fields() const;

  std::span<double> scalar(std::string_view name);
  std::span<const double> scalar(std::string_view name) const;
  std::span<Vec3> vector(std::string_view name);
  std::span<const Vec3> vector(std::string_view name) const;
  std::span<std::int32_t> integer(std::string_view name);
  std::span<const std::int32_t> integer(std::string_view name) const;
  std::span<std::uint64_t> ids();
  std::span<const std::uint64_t> ids() const;
  std::span<float> scalar_f32(std::string_view name);
  std::span<const float> scalar_f32(std::string_view name) const;
  std::span<Vec3f> vector_f32(std::string_view name);
  std::span<const Vec3f> vector_f32(std::string_view name) const;
  // A scalar or vector field by the type it is stored in (double, float,
  // Vec3 or Vec3f), for code written once for both precisions.
  template <class T>
  std::span<T> column(std::string_view name) {
    return {static_cast<T*>(column_data(name, type_of<T>())), size_};
  }
  template <class T>
  std::span<const T> column(std::string_view name) const {
    return {static_cast<const T*>(column_data(name, type_of<T>())), size_};
  }
  // f(column) with a scalar field's column in the type it is stored in (a
  // span of double or float; f is generic), and the same for a vector field
  // (Vec3 or Vec3f): for code that is not worth writing twice.
  template <class F>
  void visit_scalar(std::string_view name, F&& f) const {
    if (info(name).type == FieldType::scalar_f32)
      f(column<float>(name));
    else
      f(column<double>(name));
  }
  template <class F>
  void visit_scalar(std::string_view name, F&& f) {
    if (info(name).type == FieldType::scalar_f32)
      f(column<float>(name));
    else
      f(column<double>(name));
  }
  template <class F>
  void visit_vector(std::string_view name, F&& f) const {
    if (info(name).type == FieldType::vector_f32)
      f(column<Vec3f>(name));
    else
      f(column<Vec3>(name));
  }
  template <class F>
  void visit_vector(std::string_view name, F&& f) {
    if (info(name).type == FieldType::vector_f32)
      f(column<Vec3f>(name));
    else
      f(column<Vec3>(name));
  }
  // A scalar or vector field's values in double whatever its stored type:
  // the column itself, or its values widened into `scratch` (for code that
  // reads a field at an output, such as a writer; a pass reads the stored type).
  std::span<const double> scalar_in_double(std::string_view name, std::vector<double>& scratch) const;
  std::span<const Vec3> vector_in_double(std::string_view name, std::vector<Vec3>& scratch) const;
  // Any field as raw bytes, element_bytes(type) per particle: for code that
  // moves whole particles without knowing their fields (checkpoints, ranks).
  std::span<std::byte> bytes(std::string_view name);
  std::span<const std::byte> bytes(std::string_view name) const;

  // Frequent fields, by direct handle.
  std::span<Vec3> position() { return vector("position"); }
  std::span<const Vec3> position() const { return vector("position"); }
  std::span<std::int32_t> body() { return integer("body"); }
  std::span<const std::int32_t> body() const { return integer("body"); }
  std::span<std::int32_t> material() { return integer("material"); }
  std::span<const std::int32_t> material() const { return integer("material"); }

  // Appends n particles with zeroed fields and fresh global ids; returns the
  // index of the first one.
  std::size_t append(std::size_t n);
  // Applies a permutation: new[i] = old[order[i]] for every field.
  void reorder(std::span<const Index> order);
  // Removes particles whose flag is non-zero, keeping the order of the rest.
  std::size_t remove_if(std::span<const std::uint8_t> flags);
  void reserve(std::size_t n);

  // Appends n halo rows with zeroed fields (the caller copies the owners'
  // values, ids included); returns the index of the first one.
  std::size_t append_halo(std::size_t n);
  // Removes every halo row.
  void drop_halo();

  std::uint64_t next_id() const { return next_id_; }
  void set_next_id(std::uint64_t id) { next_id_ = id; }

 private:
  using Column = std::variant<std::vector<double>, std::vector<Vec3>, std::vector<std::int32_t>,
                              std::vector<std::uint64_t>, std::vector<float>, std::vector<Vec3f>>;
  struct Field {
    FieldInfo info;
    Column data;
  };
  Field& field(std::string_view name, FieldType type);
  const Field& field(std::string_view name, FieldType type) const;

  template <class T>
  static constexpr FieldType type_of() {
    using U = std::remove_const_t<T>;
    static_assert(std::is_same_v<U, double> || std::is_same_v<U, float> || std::is_same_v<U, Vec3> ||
                      std::is_same_v<U, Vec3f>,
                  "column<T>: T is double, float, Vec3 or Vec3f");
    if constexpr (std::is_same_v<U, double>) return FieldType::scalar;
    else if constexpr (std::is_same_v<U, float>) return FieldType::scalar_f32;
    else if constexpr (std::is_same_v<U, Vec3>) return FieldType::vector;
    else return FieldType::vector_f32;
  }
  static void widen(Field& f);  // a float column to double
  const void* column_data(std::string_view name, FieldType type) const;
  void* column_data(std::string_view name, FieldType type);

  void resize_columns(std::size_t n);
  void require_no_halo(const char* operation) const;

  std::vector<Field> fields_;
  std::size_t size_ = 0;
  std::size_t halo_ = 0;
  std::uint64_t next_id_ = 0;
  bool mixed_ = false;
};

}  // namespace talus
