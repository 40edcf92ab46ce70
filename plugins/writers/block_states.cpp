#include "block_states.hpp"

#include <vector>

#include "h5_util.hpp"
#include "h5part_series.hpp"
#include "talus/blocks.hpp"
#include "talus/error.hpp"

namespace talus::writers {

namespace {
void write_vec3(hid_t group, const char* name, const std::vector<Vec3>& v, const char* unit, const std::string& path) {
  std::vector<double> flat;
  flat.reserve(v.size() * 3);
  for (const auto& p : v) flat.insert(flat.end(), {p.x, p.y, p.z});
  h5::write_dataset(group, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, flat.data(), v.size(), 3, path);
  h5::Handle set(H5Dopen2(group, name, H5P_DEFAULT), H5Dclose);
  h5::set_attribute(set, "unit", unit, path);
}

template <class T>
void write_column(hid_t group, const char* name, const std::vector<T>& v, hid_t file_type, hid_t mem_type,
                  const char* unit, const std::string& path) {
  h5::write_dataset(group, name, file_type, mem_type, v.data(), v.size(), 0, path);
  h5::Handle set(H5Dopen2(group, name, H5P_DEFAULT), H5Dclose);
  h5::set_attribute(set, "unit", unit, path);
}
}  // namespace

void write_block_states(hid_t file, const BlockSet& blocks, std::uint64_t index, double time, std::uint64_t step,
                        const std::string& path) {
  const std::size_t n = blocks.size();
  // A stage that filled the block arrays unevenly is a bug: say which array.
  auto check_size = [&](std::size_t size, const char* what) {
    if (size != n)
      throw RunError("error: hdf5 writer: BlockSet::" + std::string(what) + " has " + std::to_string(size) +
                     " entries for " + std::to_string(n) + " blocks");
  };
  check_size(blocks.body.size(), "body");
  check_size(blocks.fixed.size(), "fixed");
  check_size(blocks.mass.size(), "mass");
  check_size(blocks.inertia.size(), "inertia");
  check_size(blocks.shape.size(), "shape");
  check_size(blocks.position.size(), "position");
  check_size(blocks.orientation.size(), "orientation");
  check_size(blocks.velocity.size(), "velocity");
  check_size(blocks.angular_velocity.size(), "angular_velocity");
  check_size(blocks.external_force.size(), "external_force");
  check_size(blocks.external_torque.size(), "external_torque");
  h5::Handle parent =
      h5::exists(file, "Blocks") ? h5::open_group(file, "Blocks", path) : h5::create_group(file, "Blocks", path);
  h5::Handle group = h5::create_group(parent, step_group(index), path);
  h5::set_attribute(group, "TimeValue", time, path);
  h5::set_attribute(group, "step", step, path);
  h5::set_attribute(group, "count", static_cast<std::uint64_t>(n), path);

  h5::write_strings(group, "name", blocks.name, path);
  write_column(group, "body", blocks.body, H5T_STD_I32LE, H5T_NATIVE_INT, "", path);
  std::vector<std::int8_t> fixed(n);
  for (std::size_t b = 0; b < n; ++b) fixed[b] = blocks.fixed[b] ? 1 : 0;
  write_column(group, "fixed", fixed, H5T_STD_I8LE, H5T_NATIVE_INT8, "", path);
  write_column(group, "mass", blocks.mass, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, "kg", path);

  std::vector<double> inertia;
  inertia.reserve(n * 9);
  for (const auto& m : blocks.inertia) inertia.insert(inertia.end(), m.begin(), m.end());
  h5::write_dataset(group, "inertia", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, inertia.data(), n, 9, path);

  write_vec3(group, "position", blocks.position, "m", path);
  std::vector<double> q;
  q.reserve(n * 4);
  for (const auto& o : blocks.orientation) q.insert(q.end(), {o.w, o.x, o.y, o.z});
  h5::write_dataset(group, "orientation", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, q.data(), n, 4, path);
  write_vec3(group, "velocity", blocks.velocity, "m/s", path);
  write_vec3(group, "angular_velocity", blocks.angular_velocity, "rad/s", path);
  write_vec3(group, "external_force", blocks.external_force, "N", path);
  write_vec3(group, "external_torque", blocks.external_torque, "N m", path);

  // Shapes in the body frame, flattened with offsets (CSR style).
  std::vector<double> vertices;
  std::vector<std::uint64_t> vertex_offset{0}, face_offset{0}, block_face_offset{0};
  std::vector<std::int32_t> face_vertices;
  for (const auto& shape : blocks.shape) {
    for (const auto& v : shape.vertices) vertices.insert(vertices.end(), {v.x, v.y, v.z});
    vertex_offset.push_back(vertices.size() / 3);
    for (const auto& face : shape.faces) {
      face_vertices.insert(face_vertices.end(), face.begin(), face.end());
      face_offset.push_back(face_vertices.size());
    }
    block_face_offset.push_back(face_offset.size() - 1);
  }
  h5::write_dataset(group, "vertices", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, vertices.data(), vertices.size() / 3, 3,
                    path);
  write_column(group, "vertex_offset", vertex_offset, H5T_STD_U64LE, H5T_NATIVE_UINT64, "", path);
  write_column(group, "face_vertices", face_vertices, H5T_STD_I32LE, H5T_NATIVE_INT32, "", path);
  write_column(group, "face_offset", face_offset, H5T_STD_U64LE, H5T_NATIVE_UINT64, "", path);
  write_column(group, "block_face_offset", block_face_offset, H5T_STD_U64LE, H5T_NATIVE_UINT64, "", path);
}

}  // namespace talus::writers
