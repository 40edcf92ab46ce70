// Builds small SPH worlds by hand for the wcsph tests, the way the host does
// (same geometry helpers, same hydrostatic start), without the scene loader.
#pragma once

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "cubic_spline.hpp"
#include "dynamic_particles.hpp"
#include "repulsion.hpp"
#include "talus/neighbour_grid.hpp"
#include "talus/geometry.hpp"
#include "talus/motion.hpp"
#include "talus/world.hpp"
#include "tait.hpp"
#include "wcsph_stage.hpp"
#include "wendland.hpp"

namespace sph_test {

using talus::Vec3;

// The parts of a body entry the boundary model reads: shape, layers, motion.
inline talus::ParamValues body_values(const std::string& json, int dim) {
  talus::ParamSet b{"body", "test body"};
  talus::declare_shape(b);
  b.integer("layers").min(1).optional();
  talus::PrescribedMotion::declare(b);
  return talus::params_from_json(b, json, dim);
}

struct SphWorld {
  talus::World world;
  std::vector<std::unique_ptr<talus::Model>> models;
  std::unique_ptr<talus::SmoothingKernel> kernel_model;
  std::unique_ptr<talus::wcsph::WcsphStage> stage;

  // The stores' precision: in mixed precision the body fields may be kept in
  // float, as the host does where the stages allow it (StageParts).
  enum class Precision { double_only, mixed };

  // dim, domain, kernel ("wendland_c2" or "cubic_spline"), h/dp, dp, gravity.
  SphWorld(int dim, Vec3 lo, Vec3 hi, double dp, double h_over_dp = 1.3, const std::string& kernel = "wendland_c2",
           Precision precision = Precision::double_only) {
    world.dim = dim;
    world.lo = lo;
    world.hi = hi;
    world.gravity = dim == 2 ? Vec3{0, -9.81, 0} : Vec3{0, 0, -9.81};
    world.dp = dp;
    world.h = h_over_dp * dp;
    const talus::ParamValues none;
    if (kernel == "cubic_spline")
      kernel_model = std::make_unique<talus::kernels::CubicSpline>(none);
    else
      kernel_model = std::make_unique<talus::kernels::WendlandC2>(none);
    world.kernel = talus::KernelTable(*kernel_model, dim, world.h);
    auto& f = world.fluid;
    const bool single = precision == Precision::mixed;
    f.set_mixed_precision(single);
    world.boundary.set_mixed_precision(single);
    f.require({"velocity", talus::FieldType::vector, "m/s", true, true, single});
    f.require({"density", talus::FieldType::scalar, "kg/m^3", true, true, single});
    f.require({"pressure", talus::FieldType::scalar, "Pa", true, true, single});
    f.require({"mass", talus::FieldType::scalar, "kg", true, true, single});
  }

  // A Tait material; returns its index.
  int water(double c0, double rho0 = 1000.0, const std::string& name = "water") {
    auto eos = std::make_unique<talus::eos::Tait>(
        talus::params_from_json(talus::eos::Tait::describe(), "{\"c0\": " + std::to_string(c0) + "}"));
    eos->set_reference_density(rho0);
    talus::Material m;
    m.name = name;
    m.density = rho0;
    m.eos = eos.get();
    models.push_back(std::move(eos));
    world.materials.push_back(std::move(m));
    return static_cast<int>(world.materials.size()) - 1;
  }

  // A fluid box [lo, hi] on the host's lattice (talus/geometry.hpp), optionally hydrostatic.
  void fluid_box(int material, Vec3 lo, Vec3 hi, bool hydrostatic, Vec3 velocity = {}) {
    const int d = world.dim;
    auto shape = body_values(std::string("{\"shape\": {\"box\": {\"min\": ") + vec(lo, d) + ", \"max\": " + vec(hi, d) +
                                 "}}}",
                             d);
    const auto pts = talus::fill_points("box", shape.alternative_values("shape"), world.dp, d, world.lo, world.hi);
    talus::Body body;
    body.name = "fluid" + std::to_string(world.bodies.size());
    body.kind = talus::BodyKind::fluid;
    body.material = material;
    body.dp = world.dp;
    body.params = shape;
    const int bi = static_cast<int>(world.bodies.size());
    world.bodies.push_back(body);
    auto& f = world.fluid;
    const std::size_t first = f.append(pts.size());
    const talus::Material& m = world.materials[material];
    const double g = talus::norm(world.gravity);
    const Vec3 up = -world.gravity / g;
    double top = -1e300;
    for (const auto& p : pts) top = std::max(top, talus::dot(p, up));
    top += 0.5 * world.dp;
    auto x = f.position();
    auto mat = f.material();
    auto bid = f.body();
    const double particle_mass =
        m.density * talus::lattice_volume("box", shape.alternative_values("shape"), world.dp, d);
    for (std::size_t k = 0; k < pts.size(); ++k) {
      const std::size_t i = first + k;
      x[i] = pts[k];
      mat[i] = material;
      bid[i] = bi;
    }
    // Each field in the type it is kept in (float in mixed precision).
    f.visit_vector("velocity", [&](auto v) { std::fill(v.begin() + first, v.end(), velocity); });
    f.visit_scalar("mass", [&](auto mass) { std::fill(mass.begin() + first, mass.end(), particle_mass); });
    f.visit_scalar("pressure", [&](auto p) {
      f.visit_scalar("density", [&](auto rho) {
        for (std::size_t k = 0; k < pts.size(); ++k) {
          const double pk = hydrostatic ? m.density * g * (top - talus::dot(pts[k], up)) : 0.0;
          p[first + k] = pk;
          rho[first + k] = hydrostatic ? m.eos->density_at(pk) : m.density;
        }
      });
    });
    world.refresh_material_index();
  }

  // A wall body with dynamic boundary particles: `shape_json` is the body's
  // "shape" value, `extra` more body members (e.g. ", \"motion\": {...}"),
  // `model_json` the model's parameters (e.g. {"method": "mdbc"}).
  talus::boundary::DynamicParticles* dbc_wall(const std::string& shape_json, int material = -1,
                                              const std::string& extra = "", const std::string& model_json = "{}") {
    auto wall = std::make_unique<talus::boundary::DynamicParticles>(talus::params_from_json(
        talus::boundary::DynamicParticles::describe(), model_json, world.dim));
    talus::Body body;
    body.name = "wall" + std::to_string(world.bodies.size());
    body.kind = talus::BodyKind::wall;
    body.material = material;
    body.dp = world.dp;
    body.boundary = wall.get();
    body.params = body_values("{\"shape\": " + shape_json + extra + "}", world.dim);
    const int bi = static_cast<int>(world.bodies.size());
    world.bodies.push_back(body);
    wall->setup(world, std::span<const int>(&bi, 1));
    auto* raw = wall.get();
    models.push_back(std::move(wall));
    return raw;
  }

  // A wall body with penalty repulsion (`model_json`: the model's parameters).
  talus::boundary::Repulsion* repulsion_wall(const std::string& shape_json, const std::string& model_json) {
    auto wall = std::make_unique<talus::boundary::Repulsion>(
        talus::params_from_json(talus::boundary::Repulsion::describe(), model_json, world.dim));
    talus::Body body;
    body.name = "wall" + std::to_string(world.bodies.size());
    body.kind = talus::BodyKind::wall;
    body.dp = world.dp;
    body.boundary = wall.get();
    body.params = body_values("{\"shape\": " + shape_json + "}", world.dim);
    const int bi = static_cast<int>(world.bodies.size());
    world.bodies.push_back(body);
    wall->setup(world, std::span<const int>(&bi, 1));
    auto* raw = wall.get();
    models.push_back(std::move(wall));
    return raw;
  }

  // Creates and sets up the wcsph stage with the given parameters (JSON).
  talus::wcsph::WcsphStage& make_stage(const std::string& json = "{}") {
    stage = std::make_unique<talus::wcsph::WcsphStage>(
        talus::params_from_json(talus::wcsph::WcsphStage::describe(), json, world.dim));
    stage->setup(world);
    return *stage;
  }

  // One host step: dt from the stage, advance, clock, and the host's re-sort
  // of the fluid by cell every 25 steps (its default), for cache locality.
  double step(double dt_max = 1e30) {
    const double dt = std::min(dt_max, stage->stable_time_step(world));
    stage->advance(world, dt);
    world.time += dt;
    ++world.step;
    if (world.step % 25 == 0) {
      talus::NeighbourGrid cells;
      cells.configure(world.dim, world.lo, world.hi, world.kernel.support_radius(), {});
      cells.build(world.fluid.position());
      world.fluid.reorder(cells.order());
      world.refresh_material_index();
    }
    return dt;
  }

  static std::string vec(const Vec3& v, int dim) {
    std::string s = "[" + num(v.x) + ", " + num(v.y);
    if (dim == 3) s += ", " + num(v.z);
    return s + "]";
  }
  static std::string num(double x) {
    char b[64];
    std::snprintf(b, sizeof b, "%.17g", x);
    return b;
  }
};

}  // namespace sph_test
