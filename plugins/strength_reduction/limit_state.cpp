#include "limit_state.hpp"

#include <cstdio>

#include "file_io.hpp"
#include "h5_util.hpp"
#include "slip_path.hpp"

namespace talus::strength_reduction {
namespace {

namespace h5 = writers::h5;

void write_vectors(hid_t group, const char* name, const std::vector<Vec3>& v, const std::string& path) {
  std::vector<double> flat;
  flat.reserve(3 * v.size());
  for (const Vec3& p : v) flat.insert(flat.end(), {p.x, p.y, p.z});
  h5::write_dataset(group, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, flat.data(), v.size(), 3, path);
}

void write_reals(hid_t group, const char* name, const std::vector<double>& v, const std::string& path) {
  h5::write_dataset(group, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, v.data(), v.size(), 0, path);
}

void write_group(hid_t file, const char* name, const LimitState& s, const std::string& path) {
  if (!s.present) return;
  h5::Handle g = h5::create_group(file, name, path);
  h5::set_attribute(g, "factor", s.factor, path);
  h5::set_attribute(g, "steps", static_cast<std::int64_t>(s.steps), path);
  h5::set_attribute(g, "unbalanced_ratio", s.ratio, path);
  write_vectors(g, "point", s.point, path);
  write_vectors(g, "normal", s.normal, path);
  write_vectors(g, "force", s.force, path);
  write_reals(g, "normal_force", s.normal_force, path);
  write_reals(g, "shear_force", s.shear_force, path);
  write_reals(g, "area", s.area, path);
  write_reals(g, "gap", s.gap, path);
  h5::write_dataset(g, "state", H5T_STD_U8LE, H5T_NATIVE_UINT8, s.state.data(), s.state.size(), 0, path);
  h5::write_dataset(g, "bonded", H5T_STD_U8LE, H5T_NATIVE_UINT8, s.bonded.data(), s.bonded.size(), 0, path);
  h5::write_dataset(g, "block_a", H5T_STD_U32LE, H5T_NATIVE_UINT32, s.block_a.data(), s.block_a.size(), 0, path);
  h5::write_dataset(g, "block_b", H5T_STD_U32LE, H5T_NATIVE_UINT32, s.block_b.data(), s.block_b.size(), 0, path);
  write_vectors(g, "block_position", s.position, path);
  write_vectors(g, "block_displacement", s.displacement, path);
  std::vector<double> q;
  for (const Quaternion& o : s.orientation) q.insert(q.end(), {o.w, o.x, o.y, o.z});
  h5::write_dataset(g, "block_orientation", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, q.data(), s.orientation.size(), 4,
                    path);
  h5::write_dataset(g, "block_released", H5T_STD_U8LE, H5T_NATIVE_UINT8, s.released.data(), s.released.size(), 0,
                    path);
}

}  // namespace

LimitState capture(const TrialResult& trial, const dda::ContactSet& c, const BlockSet& blocks,
                   const std::vector<Vec3>& start_position, const std::vector<std::uint32_t>& rigid_body) {
  LimitState s;
  s.present = true;
  s.factor = trial.factor;
  s.steps = trial.steps;
  s.ratio = trial.ratio;
  s.point = c.point;
  s.normal = c.normal;
  s.force = c.force;
  s.area = c.area;
  s.gap = c.gap;
  for (std::size_t k = 0; k < c.size(); ++k) {
    const double fn = dot(c.force[k], c.normal[k]);
    s.normal_force.push_back(fn);
    s.shear_force.push_back(norm(c.force[k] - fn * c.normal[k]));
    s.state.push_back(c.state[k] & dda::contact_state_mask);
    s.bonded.push_back((c.state[k] & dda::contact_bonded) ? 1 : 0);
    s.block_a.push_back(c.key[k].a);
    s.block_b.push_back(c.key[k].b);
  }
  s.position = blocks.position;
  s.orientation = blocks.orientation;
  for (std::size_t i = 0; i < blocks.size(); ++i) s.displacement.push_back(blocks.position[i] - start_position[i]);
  s.released.assign(blocks.size(), 0);
  for (const std::uint32_t i : released_blocks(blocks, c, rigid_body).blocks) s.released[i] = 1;
  return s;
}

double release_moved_blocks(LimitState& failed, const LimitState& stable) {
  double held = 0.0;
  for (const Vec3& d : stable.displacement) held = std::max(held, norm(d));
  for (std::size_t i = 0; i < failed.displacement.size(); ++i) failed.released[i] = norm(failed.displacement[i]) > held;
  return held;
}

void write_limit_state(const std::string& path, const BlockSet& blocks, const LimitState& stable,
                       const LimitState& failed) {
  const std::string tmp = path + ".tmp";
  {
    h5::QuietErrors quiet;
    h5::Handle file = h5::create_file(tmp);
    h5::set_attribute(file, "contact_state_codes", "0 open, 1 closed (stick), 2 slip", tmp);
    h5::write_strings(file, "block_name", blocks.name, tmp);
    write_group(file, "stable", stable, tmp);
    write_group(file, "failed", failed, tmp);
    if (!file.close()) h5::check(herr_t{-1}, "cannot close", tmp);
  }
  writers::publish(tmp, path, false);
}

}  // namespace talus::strength_reduction
