// A hand-built plan-view World for the run-out tests (what the host does for
// a scene: fluid particles on a lattice, materials, the tabulated kernel),
// plus helpers to run the stage and sample the depth.
#pragma once

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "cubic_spline.hpp"
#include "depth_integrated_sph.hpp"
#include "talus/params.hpp"
#include "talus/rheology.hpp"
#include "talus/world.hpp"

namespace talus::runout::test {

struct RunoutWorld {
  World world;
  std::vector<std::unique_ptr<Rheology>> rheologies;
  std::unique_ptr<DepthIntegratedSph> stage;

  RunoutWorld(Vec3 lo, Vec3 hi, double dp, double h_over_dp = 1.3, std::array<bool, 3> periodic = {}) {
    world.dim = 2;
    world.lo = lo;
    world.hi = hi;
    world.periodic = periodic;
    world.gravity = {0.0, -9.81, 0.0};
    world.dp = dp;
    world.h = h_over_dp * dp;
    const kernels::CubicSpline spline{ParamValues{}};
    world.kernel = KernelTable(spline, 2, world.h);
    world.fluid.require({"velocity", FieldType::vector, "m/s", true, true});
    world.fluid.require({"mass", FieldType::scalar, "kg", true, true});
  }

  // rheology may be null (frictionless).
  int add_material(const std::string& name, double density, std::unique_ptr<Rheology> rheology) {
    Material m;
    m.name = name;
    m.density = density;
    m.rheology = rheology.get();
    rheologies.push_back(std::move(rheology));
    world.materials.push_back(std::move(m));
    return static_cast<int>(world.materials.size()) - 1;
  }

  // Lattice of spacing dp filling [lo, hi] in plan, first points dp/2 inside.
  void fill_box(Vec3 lo, Vec3 hi, int material, Vec3 velocity = {}) {
    Body b;
    b.name = "mass" + std::to_string(world.bodies.size());
    b.kind = BodyKind::fluid;
    b.material = material;
    b.dp = world.dp;
    world.bodies.push_back(b);
    const int nx = static_cast<int>(std::round((hi.x - lo.x) / world.dp));
    const int ny = static_cast<int>(std::round((hi.y - lo.y) / world.dp));
    const std::size_t first = world.fluid.append(static_cast<std::size_t>(nx) * ny);
    auto pos = world.fluid.position();
    auto vel = world.fluid.vector("velocity");
    auto mat = world.fluid.material();
    auto body = world.fluid.body();
    std::size_t k = first;
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i, ++k) {
        pos[k] = {lo.x + (i + 0.5) * world.dp, lo.y + (j + 0.5) * world.dp, 0.0};
        vel[k] = velocity;
        mat[k] = material;
        body[k] = static_cast<int>(world.bodies.size()) - 1;
      }
  }

  DepthIntegratedSph& make_stage(const std::string& json, double end_time) {
    world.end_time = end_time;
    world.refresh_material_index();
    stage = std::make_unique<DepthIntegratedSph>(params_from_json(DepthIntegratedSph::describe(), json, 2));
    stage->setup(world);
    return *stage;
  }

  // Runs the stage to `t_end` as the host does (dt from the stage, last step
  // trimmed to land on t_end). Returns the number of steps.
  int run_to(double t_end) {
    int steps = 0;
    while (world.time < t_end - 1e-12) {
      double dt = std::min(stage->stable_time_step(world), t_end - world.time);
      stage->advance(world, dt);
      world.time += dt;
      ++world.step;
      ++steps;
    }
    return steps;
  }

  // Slope-normal depth at plan point x by SPH interpolation (scatter, each
  // particle's smoothing length), with the slope cosine `cosine`.
  double depth_at(Vec3 x, double cosine = 1.0) const {
    const VariableKernel k(world.kernel);
    auto pos = world.fluid.position();
    auto vol = world.fluid.scalar("volume");
    auto ell = world.fluid.scalar("smoothing_length");
    double s = 0.0;
    for (std::size_t j = 0; j < world.fluid.size(); ++j) {
      Vec3 d = x - pos[j];
      for (int a = 0; a < 2; ++a)
        if (world.periodic[a]) d[a] -= (world.hi[a] - world.lo[a]) * std::round(d[a] / (world.hi[a] - world.lo[a]));
      const double r = norm(d);
      if (r < k.support * ell[j]) s += vol[j] * k.w(r, ell[j]);
    }
    return s * cosine;
  }

  double max_x() const {
    double m = -1e300;
    for (const Vec3& p : world.fluid.position()) m = std::max(m, p.x);
    return m;
  }
};

}  // namespace talus::runout::test
