#include "block_link.hpp"

#include <algorithm>
#include <cmath>
#include <set>

#include "talus/blocks.hpp"
#include "talus/dda/polyhedron.hpp"
#include "talus/error.hpp"
#include "talus/parallel.hpp"
#include "talus/state_archive.hpp"
#include "talus/world.hpp"

namespace talus::coupling {

std::vector<std::size_t> find_blocks(const World& world, std::span<const int> bodies, const std::string& model) {
  std::vector<std::size_t> out;
  for (int bi : bodies) {
    const Body& body = world.bodies[bi];
    if (body.kind != BodyKind::block)
      body.params.fail("boundary", "'" + model + "' is a boundary for block bodies; '" + body.name + "' is a " +
                                       to_string(body.kind) + " body (use dynamic_particles for walls)");
    if (!world.blocks)
      throw InputError("error: " + body.params.file() +
                       ": /pipeline: block '" + body.name + "' has boundary '" + model +
                       "', which needs the blocks of the dda stage when the fluid stage sets up; list "
                       "{\"stage\": \"dda\"} before {\"stage\": \"wcsph\"} in the pipeline");
    const auto& owner = world.blocks->body;
    const auto it = std::find(owner.begin(), owner.end(), bi);
    if (it == owner.end())
      throw InputError("error: " + body.params.file() + ": /pipeline: block '" + body.name +
                       "' is not among the dda stage's blocks; list {\"stage\": \"dda\"} before the fluid stage");
    out.push_back(static_cast<std::size_t>(it - owner.begin()));
  }
  return out;
}

std::size_t clear_fluid_inside(World& world, std::span<const std::size_t> blocks, double clearance) {
  ParticleStore& fluid = world.fluid;
  const std::size_t n = fluid.size();
  if (n == 0 || blocks.empty()) return 0;
  const BlockSet& b = *world.blocks;
  const auto x = fluid.position();
  std::vector<std::uint8_t> inside(n, 0);
  std::size_t count = 0;
  for (std::size_t k : blocks) {
    const Vec3 pad{clearance, clearance, clearance};
    const Vec3 lo = b.bounds_lo[k] - pad, hi = b.bounds_hi[k] + pad;
    for (std::size_t i = 0; i < n; ++i) {
      if (inside[i]) continue;
      const Vec3 p = nearest_image(world, x[i], b.position[k]);
      if (p.x < lo.x || p.y < lo.y || p.z < lo.z || p.x > hi.x || p.y > hi.y || p.z > hi.z) continue;
      const Vec3 body_point = rotate_inverse(b.orientation[k], p - b.position[k]);
      if (dda::plane_distance(b.shape[k], body_point) < clearance) {
        inside[i] = 1;
        ++count;
      }
    }
  }
  if (count) {
    fluid.remove_if(inside);
    world.refresh_material_index();
  }
  return count;
}

int coupling_material(const World& world, int body, const std::string& model, const std::string& name) {
  const Body& b = world.bodies[body];
  if (!name.empty()) {
    const int m = world.find_material(name);
    if (m < 0) b.params.fail("boundary", "'" + model + "': material '" + name + "' is not in \"materials\"");
    return m;
  }
  std::set<int> fluid;
  for (const Body& other : world.bodies)
    if (other.kind == BodyKind::fluid && other.material >= 0) fluid.insert(other.material);
  if (fluid.size() != 1)
    b.params.fail("boundary", "'" + model + "' of block '" + b.name + "' needs \"material\" (the fluid it touches) "
                              "when the scene has " + std::to_string(fluid.size()) + " fluid materials");
  return *fluid.begin();
}

void ImpulseLedger::reset(std::size_t n) {
  for (auto* v : {&force_, &torque_, &owed_, &owed_angular_, &owed_start_, &owed_angular_start_, &given_,
                  &given_start_, &committed_, &committed_torque_, &applied_, &applied_torque_})
    v->assign(n, Vec3{});
  share_.assign(6 * n, 0.0);
}

std::string ImpulseLedger::save_state() const {
  StateWriter w;
  for (const auto* v : {&force_, &torque_, &owed_, &owed_angular_, &given_, &committed_, &committed_torque_})
    w.vector(*v);
  return std::move(w.out);
}

void ImpulseLedger::load_state(std::string_view bytes, const char* what) {
  StateReader r{bytes, what};
  const std::size_t n = force_.size();
  for (auto* v : {&force_, &torque_, &owed_, &owed_angular_, &given_, &committed_, &committed_torque_}) {
    r.vector(*v);
    if (v->size() != n)
      throw InputError(std::string("error: checkpoint: ") + what + " is for " + std::to_string(v->size()) +
                       " blocks, this scene has " + std::to_string(n));
    for (const Vec3& x : *v)
      if (!std::isfinite(x.x) || !std::isfinite(x.y) || !std::isfinite(x.z))
        throw InputError(std::string("error: checkpoint: ") + what + " holds a non-finite force or impulse");
  }
  r.finish();
}

void ImpulseLedger::begin_step() {
  // The dda stage ran first in this host step: it applied the committed force
  // over the step and cleared external_force.
  applied_ = committed_;
  applied_torque_ = committed_torque_;
  std::fill(committed_.begin(), committed_.end(), Vec3{});
  std::fill(committed_torque_.begin(), committed_torque_.end(), Vec3{});
  owed_start_ = owed_;
  owed_angular_start_ = owed_angular_;
  given_start_ = given_;
}

void ImpulseLedger::commit(World& world, std::span<const std::size_t> blocks, double time, double dt) {
  const double host_dt = time - world.time;  // the last commit of a step has time = t^n + dt
  if (!(host_dt > 0.0)) return;
  sums_ = share_;
  world.parallel().sum(sums_);
  for (std::size_t k = 0; k < blocks.size(); ++k) {
    force_[k] = {sums_[6 * k + 0], sums_[6 * k + 1], sums_[6 * k + 2]};
    torque_[k] = {sums_[6 * k + 3], sums_[6 * k + 4], sums_[6 * k + 5]};
  }
  BlockSet& b = *world.blocks;
  for (std::size_t k = 0; k < blocks.size(); ++k) {
    const std::size_t i = blocks[k];
    given_[k] = given_start_[k] + force_[k] * dt;
    owed_[k] = owed_start_[k] + force_[k] * dt - applied_[k] * host_dt;
    owed_angular_[k] = owed_angular_start_[k] + torque_[k] * dt - applied_torque_[k] * host_dt;
    // Held over the next host step; if that step has the same dt the debt is paid exactly.
    const Vec3 f = owed_[k] / host_dt, t = owed_angular_[k] / host_dt;
    b.external_force[i] += f - committed_[k];
    b.external_torque[i] += t - committed_torque_[k];
    committed_[k] = f;
    committed_torque_[k] = t;
  }
}

void ImpulseLedger::add_impulses(World& world, std::span<const std::size_t> blocks, std::span<const Vec3> impulse,
                                 std::span<const Vec3> angular, double time) {
  const std::size_t n = blocks.size();
  sums_.assign(6 * n, 0.0);
  for (std::size_t k = 0; k < n; ++k)
    for (int a = 0; a < 3; ++a) {
      sums_[6 * k + a] = impulse[k][a];
      sums_[6 * k + 3 + a] = angular[k][a];
    }
  world.parallel().sum(sums_);
  const double host_dt = time - world.time;
  if (!(host_dt > 0.0)) return;
  BlockSet& b = *world.blocks;
  for (std::size_t k = 0; k < n; ++k) {
    const Vec3 j{sums_[6 * k + 0], sums_[6 * k + 1], sums_[6 * k + 2]};
    const Vec3 l{sums_[6 * k + 3], sums_[6 * k + 4], sums_[6 * k + 5]};
    if (j == Vec3{} && l == Vec3{}) continue;
    given_[k] += j;
    owed_[k] += j;
    owed_angular_[k] += l;
    const Vec3 f = j / host_dt, t = l / host_dt;
    b.external_force[blocks[k]] += f;
    b.external_torque[blocks[k]] += t;
    committed_[k] += f;
    committed_torque_[k] += t;
  }
}

}  // namespace talus::coupling
