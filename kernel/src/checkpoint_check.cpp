#include "checkpoint_check.hpp"

#include <cmath>
#include <cstdint>
#include <sstream>

#include "checkpoint.hpp"
#include "talus/blocks.hpp"
#include "talus/error.hpp"
#include "talus/world.hpp"

namespace talus {

namespace {

struct Checker {
  const std::string& path;
  const World& world;

  [[noreturn]] void fail(const std::string& what) const { throw InputError("error: checkpoint " + path + ": " + what); }

  static std::string text(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
  }

  // Walls, moving pistons and blocks may leave the domain, but not by more
  // than its own size: beyond that a coordinate is damage, not motion.
  bool far_outside(const Vec3& x) const {
    for (int a = 0; a < world.dim; ++a) {
      const double span = std::max(world.hi[a] - world.lo[a], world.dp);
      if (x[a] < world.lo[a] - 10.0 * span || x[a] > world.hi[a] + 10.0 * span) return true;
    }
    return false;
  }

  void clock(const RunState& state) const {
    if (!std::isfinite(world.time) || world.time < 0.0 || world.time > world.end_time * (1.0 + 1e-9) + 1e-300)
      fail("time " + text(world.time) + " s is outside the run [0, " + text(world.end_time) + "] s");
    if (!(state.last_output_time == -1.0 || (std::isfinite(state.last_output_time) &&
                                             state.last_output_time >= 0.0 && state.last_output_time <= world.time)))
      fail("last output time " + text(state.last_output_time) + " s is not within [0, " + text(world.time) + "] s");
    if (state.writer_next_step.size() != state.writer_next_time.size())
      fail("it has " + std::to_string(state.writer_next_time.size()) + " output times but " +
           std::to_string(state.writer_next_step.size()) + " output steps");
    for (std::size_t i = 0; i < state.writer_next_time.size(); ++i)
      if (!std::isfinite(state.writer_next_time[i]) || state.writer_next_time[i] < 0.0)
        fail("output " + std::to_string(i + 1) + ": next output time " + text(state.writer_next_time[i]) +
             " s is not a time");
  }

  void store(const ParticleStore& s, const char* which, bool fluid) const {
    const std::size_t n = s.size();
    const auto id = s.ids();
    const auto body = s.body();
    const auto material = s.material();
    const auto x = s.position();
    const int bodies = static_cast<int>(world.bodies.size());
    const int materials = static_cast<int>(world.materials.size());
    auto particle = [&](std::size_t i) { return std::string(which) + " particle " + std::to_string(i); };
    for (std::size_t i = 0; i < n; ++i) {
      if (id[i] >= s.next_id())
        fail(particle(i) + " has id " + std::to_string(id[i]) + ", not below the next id " + std::to_string(s.next_id()));
      if (body[i] < 0 || body[i] >= bodies)
        fail(particle(i) + " has body index " + std::to_string(body[i]) + "; the scene has " + std::to_string(bodies) +
             " bodies");
      const Body& b = world.bodies[body[i]];
      if (fluid && b.kind != BodyKind::fluid)
        fail(particle(i) + " belongs to body '" + b.name + "', which is a " + to_string(b.kind) + ", not a fluid");
      if (!fluid && !b.boundary)
        fail(particle(i) + " belongs to body '" + b.name + "', which has no boundary particles");
      if (material[i] < -1 || material[i] >= materials || (fluid && material[i] < 0))
        fail(particle(i) + " has material index " + std::to_string(material[i]) + "; the scene has " +
             std::to_string(materials) + " materials");
      if (fluid && material[i] != b.material)
        fail(particle(i) + " has material index " + std::to_string(material[i]) + ", its body '" + b.name +
             "' has material " + std::to_string(b.material));
      if (!is_finite(x[i])) fail(particle(i) + " has a non-finite position");
      if (fluid) {
        // Fluid outside the domain is removed after every step, so none is saved there.
        for (int a = 0; a < world.dim; ++a) {
          const double slack = 1e-9 * std::max(world.hi[a] - world.lo[a], world.dp);
          if (x[i][a] < world.lo[a] - slack || x[i][a] > world.hi[a] + slack)
            fail(particle(i) + " at " + axis_text(x[i]) + " is outside the domain");
        }
      } else if (far_outside(x[i])) {
        fail(particle(i) + " at " + axis_text(x[i]) + " is far outside the domain");
      }
    }
    for (const auto& f : s.fields()) {
      if (double_type(f.type) == FieldType::scalar)
        s.visit_scalar(f.name, [&](auto v) {
          for (std::size_t i = 0; i < n; ++i)
            if (!std::isfinite(v[i])) fail(particle(i) + " has non-finite " + f.name + " (" + text(v[i]) + ")");
        });
      else if (double_type(f.type) == FieldType::vector)
        s.visit_vector(f.name, [&](auto v) {
          for (std::size_t i = 0; i < n; ++i)
            if (!is_finite(v[i])) fail(particle(i) + " has a non-finite " + f.name);
        });
    }
    if (fluid)
      for (const char* name : {"mass", "density"}) {
        if (!s.has(name)) continue;  // not every pipeline reads them
        s.visit_scalar(name, [&](auto v) {
          for (std::size_t i = 0; i < n; ++i)
            if (!(v[i] > 0.0)) fail(particle(i) + " has " + name + " " + text(v[i]) + ", not > 0");
        });
      }
  }

  std::string axis_text(const Vec3& x) const {
    return "(" + text(x.x) + ", " + text(x.y) + (world.dim == 3 ? ", " + text(x.z) : "") + ")";
  }

  void blocks() const {
    if (!world.blocks) return;
    const BlockSet& b = *world.blocks;
    for (std::size_t i = 0; i < b.size(); ++i) {
      const std::string block = "block '" + b.name[i] + "'";
      const Quaternion& q = b.orientation[i];
      if (!is_finite(b.position[i]) || far_outside(b.position[i]))
        fail(block + " has its centroid at " + axis_text(b.position[i]) + ", far outside the domain");
      const double norm2 = q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z;
      if (!std::isfinite(norm2) || std::abs(norm2 - 1.0) > 1e-6)
        fail(block + " has an orientation that is not a unit quaternion (norm^2 = " + text(norm2) + ")");
      if (!is_finite(b.velocity[i]) || !is_finite(b.angular_velocity[i]) || !is_finite(b.external_force[i]) ||
          !is_finite(b.external_torque[i]))
        fail(block + " has a non-finite velocity, angular velocity or external load");
    }
  }
};

}  // namespace

void check_restored_state(const std::string& path, const World& world, const RunState& state) {
  const Checker c{path, world};
  c.clock(state);
  c.store(world.fluid, "fluid", true);
  c.store(world.boundary, "boundary", false);
  c.blocks();
}

}  // namespace talus
