#include "repulsion.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "talus/error.hpp"
#include "talus/world.hpp"

namespace talus::boundary {

ParamSet Repulsion::describe() {
  ParamSet p{"repulsion", "penalty walls F = max(0, K_s d - (v.n) K_d) n against planes and meshes (rock-fluid seed eq. 22)"};
  p.real("stiffness").unit("N/m").greater_than(0.0).doc("penalty stiffness K_s per fluid particle");
  p.real("damping").unit("N s/m").min(0.0).default_value(0.0).doc("damping K_d on the normal velocity");
  p.real("distance").unit("m").greater_than(0.0).optional().doc(
      "activation distance r0 from the surface (default: the wall body's dp)");
  return p;
}

Repulsion::Repulsion(const ParamValues& v)
    : spring_{v.real("stiffness"), v.real("damping")},
      has_distance_(v.has("distance")),
      distance_(v.has("distance") ? v.real("distance") : 0.0) {}

void Repulsion::setup(World& world, std::span<const int> bodies) {
  for (int bi : bodies) {
    const Body& body = world.bodies[bi];
    const ParamValues& v = body.params;
    if (v.has("motion")) v.fail("motion", "repulsion walls do not move yet; use dynamic_particles for a moving wall");
    const double r0 = has_distance_ ? distance_ : (body.dp > 0 ? body.dp : world.dp);
    if (!(r0 > 0)) v.fail("dp", "repulsion needs an activation distance: give the body a \"dp\" or the model a \"distance\"");
    const std::string& alt = v.alternative("shape");
    const ParamValues& s = v.alternative_values("shape");
    if (alt == "half_space") {
      // The solid is behind the plane (side opposite the normal); the fluid in front.
      const Vec3 n = s.vector("normal");
      const double len = norm(n);
      if (!(len > 0)) s.fail("normal", "must not be zero");
      planes_.push_back({s.vector("point"), n / len, r0});
    } else if (alt == "box_walls") {
      const Vec3 lo = s.vector("min"), hi = s.vector("max");
      const auto& open = s.strings("open");
      auto is_open = [&](const std::string& f) { return std::find(open.begin(), open.end(), f) != open.end(); };
      const char* axes = "xyz";
      for (int a = 0; a < world.dim; ++a) {
        Vec3 n{};
        n[a] = 1.0;
        if (!is_open(std::string("-") + axes[a])) planes_.push_back({lo, n, r0});
        if (!is_open(std::string("+") + axes[a])) planes_.push_back({hi, -n, r0});
      }
    } else if (alt == "mesh") {
      Mesh m{s.read_file("file", [](const std::string& f) { return load_mesh(f); }), {}, {}, r0};
      const double scale = s.real("scale");
      const Vec3 offset = s.vector("offset");
      for (Vec3& p : m.mesh.vertices) p = p * scale + offset;
      m.mesh.bounds(m.lo, m.hi);
      m.lo -= Vec3{r0, r0, r0};
      m.hi += Vec3{r0, r0, r0};
      meshes_.push_back(std::move(m));
    } else {
      v.fail("shape", "repulsion walls are planes or meshes; allowed: half_space, box_walls, mesh");
    }
    body_names_.push_back(body.name);
  }
}

void Repulsion::bind(World& world, const sph::FluidSettings&) {
  min_mass_ = std::numeric_limits<double>::infinity();
  for (double m : world.fluid.scalar("mass")) min_mass_ = std::min(min_mass_, m);
}

std::uint64_t Repulsion::add_direct_forces(World&, const sph::FluidView& fluid, const sph::FluidRates& rates) {
  const std::size_t n = fluid.position.size();
  const sph::PenaltySpring spring = spring_;
  const Plane* planes = planes_.data();
  const std::size_t np = planes_.size();
#pragma omp parallel for schedule(static) if (n >= 4096)
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 x = fluid.position[i], v = fluid.velocity[i];
    Vec3 force{};
    for (std::size_t k = 0; k < np; ++k) {
      const Plane& pl = planes[k];
      const double d = pl.r0 - dot(x - pl.point, pl.normal);
      if (d > 0.0) force += pl.normal * spring.normal_force(d, dot(v, pl.normal));
    }
    for (const Mesh& m : meshes_) {
      bool near = true;
      for (int a = 0; a < 3; ++a) near = near && x[a] >= m.lo[a] && x[a] <= m.hi[a];
      if (!near) continue;
      Vec3 closest;
      const double dist = m.mesh.distance(x, &closest);
      const bool inside = m.mesh.contains(x);
      if (!inside && dist >= m.r0) continue;
      // Normal out of the solid, towards the fluid side.
      Vec3 nrm = dist > 0 ? (x - closest) / dist : Vec3{};
      if (inside) nrm = -nrm;
      const double d = inside ? m.r0 + dist : m.r0 - dist;
      force += nrm * spring.normal_force(d, dot(v, nrm));
    }
    rates.acceleration[i] += force / fluid.mass[i];
  }
  return 0;
}

double Repulsion::stable_time_step(const World&) const { return spring_.stable_time_step(min_mass_); }

void Repulsion::describe_passes(StagePlan& plan) const {
  std::string names;
  for (const auto& b : body_names_) names += (names.empty() ? "'" : ", '") + b + "'";
  plan.passes.push_back("fluid-wall penalty pass (repulsion " + names + "): " + std::to_string(planes_.size()) +
                        " planes, " + std::to_string(meshes_.size()) + " meshes");
}

}  // namespace talus::boundary
