// The modified dynamic boundary condition (sph/ghost_nodes.hpp, the "mdbc"
// method of dynamic_particles): the ghost-node extrapolation continues a
// linear pressure and a linear shear flow exactly behind a wall, falls back
// to Shepard and to zero where the fluid is too thin; free-slip walls exert
// no drag on a stream along them, no-slip ones the mirrored drag; a tank of
// water at rest stays at rest on mDBC walls with the floor pressure rho0 g H.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "newtonian.hpp"
#include "sph_world.hpp"
#include "talus/error.hpp"
#include "talus/sph/ghost_nodes.hpp"

namespace {

using sph_test::SphWorld;
using talus::Vec3;

// Fluid on a 2D lattice of spacing dp filling [0, 1] x [0, depth] over a floor
// at y = 0, with pressure p(y) and velocity v(y); wall particles at
// x = 0.5, y = -(k + 1/2) dp for k < layers, their ghost nodes mirrored
// across the floor.
struct FloorCase {
  double dp = 0.02;
  talus::KernelTable kernel;
  std::unique_ptr<talus::SmoothingKernel> model;
  std::vector<Vec3> x, v;
  std::vector<double> rho, p, mass, inv_rho;
  talus::NeighbourGrid cells;
  std::vector<Vec3> wall, ghost, wall_v;

  template <class Pressure, class Velocity>
  FloorCase(double depth, int layers, Pressure pressure, Velocity velocity) {
    model = std::make_unique<talus::kernels::WendlandC2>(talus::ParamValues{});
    kernel = talus::KernelTable(*model, 2, 1.5 * dp);
    for (double y = 0.5 * dp; y < depth; y += dp)
      for (double px = 0.5 * dp; px < 1.0; px += dp) {
        x.push_back({px, y, 0});
        v.push_back(velocity(y));
        p.push_back(pressure(y));
        rho.push_back(1000.0 + 1e-3 * y);      // any density: V_j = m_j / rho_j = dp^2 exactly
        mass.push_back(rho.back() * dp * dp);
        inv_rho.push_back(1.0 / rho.back());
      }
    cells.configure(2, {0, -1, 0}, {1, 1, 0}, kernel.support_radius(), {});
    cells.build(x);
    for (int k = 0; k < layers; ++k) {
      wall.push_back({0.5, -(k + 0.5) * dp, 0});
      ghost.push_back({0.5, (k + 0.5) * dp, 0});
      wall_v.push_back({});
    }
  }
  talus::sph::FluidView view() const {
    talus::sph::FluidView f;
    f.cells = &cells;
    f.position = x;
    f.velocity = v;
    f.density = rho;
    f.pressure = p;
    f.mass = mass;
    f.inv_density = inv_rho;
    return f;
  }
  void extrapolate(talus::sph::WallSlip slip, std::vector<double>& out_p, std::vector<Vec3>& out_v) const {
    out_p.assign(wall.size(), -1.0);
    out_v.assign(wall.size(), Vec3{});
    talus::sph::extrapolate_from_ghost_nodes(2, {wall, ghost, wall_v}, view(), kernel, slip, out_p, out_v);
  }
};

TEST(GhostNodes, HydrostaticPressureAndShearFlowContinueExactlyBehindTheWall) {
  const double gradient = 9810.0, shear = 3.0, inflow = -0.2;  // p = 2943 - 9810 y, v = (shear y, inflow)
  FloorCase c(0.3, 3, [&](double y) { return gradient * (0.3 - y); }, [&](double y) { return Vec3{shear * y, inflow, 0}; });
  std::vector<double> p;
  std::vector<Vec3> v;
  c.extrapolate(talus::sph::WallSlip::no_slip, p, v);
  for (std::size_t b = 0; b < c.wall.size(); ++b) {
    const double y = c.wall[b].y;
    EXPECT_NEAR(p[b], gradient * (0.3 - y), 1e-8) << "layer " << b;
    // No-slip: 2 v_wall - v_ghost, the shear flow continued through the wall, the inflow reversed.
    EXPECT_NEAR(v[b].x, shear * y, 1e-11) << "layer " << b;
    EXPECT_NEAR(v[b].y, -inflow, 1e-11) << "layer " << b;
  }
  c.extrapolate(talus::sph::WallSlip::free_slip, p, v);
  for (std::size_t b = 0; b < c.wall.size(); ++b) {
    EXPECT_NEAR(v[b].x, -shear * c.wall[b].y, 1e-11) << "free slip keeps the ghost's tangential velocity";
    EXPECT_NEAR(v[b].y, -inflow, 1e-11) << "and mirrors its normal one";
  }
}

TEST(GhostNodes, ThinFluidFallsBackToShepardAndNoFluidToZero) {
  // One row of fluid: the moment matrix has no vertical extent (det ~ 0), so
  // the ghost node takes the Shepard mean, here the row's pressure itself.
  FloorCase thin(0.02, 1, [](double) { return 30.0; }, [](double) { return Vec3{0.1, 0, 0}; });
  std::vector<double> p;
  std::vector<Vec3> v;
  thin.extrapolate(talus::sph::WallSlip::no_slip, p, v);
  EXPECT_NEAR(p[0], 30.0, 1e-9);
  EXPECT_NEAR(v[0].x, -0.1, 1e-12);
  // A ghost node far above the fluid: nothing to extrapolate, zero pressure and the wall's own velocity.
  FloorCase far(0.3, 1, [](double) { return 30.0; }, [](double) { return Vec3{0.1, 0, 0}; });
  far.ghost[0] = {0.5, 0.9, 0};
  far.extrapolate(talus::sph::WallSlip::no_slip, p, v);
  EXPECT_EQ(p[0], 0.0);
  EXPECT_EQ(v[0].x, 0.0);
}

// Fluid at rho0 streaming uniformly at (u, 0) over a floor at rest, no
// gravity: what acts on it is the wall's viscous drag only. Returns the
// fluid's accelerations.
std::vector<Vec3> drag(const std::string& model_json, const std::string& stage_json) {
  SphWorld s(2, {0, -0.1, 0}, {0.4, 0.3, 0}, 0.02, 1.5);
  s.world.periodic = {true, false, false};
  s.world.gravity = {};
  const int water = s.water(1.0);
  auto rheology = std::make_unique<talus::rheology::Newtonian>(
      talus::params_from_json(talus::rheology::Newtonian::describe(), R"({"viscosity": 1e-3})"));
  s.world.materials[water].rheology = rheology.get();
  s.models.push_back(std::move(rheology));
  s.fluid_box(water, {0, 0, 0}, {0.4, 0.2, 0}, false, Vec3{0.01, 0, 0});
  s.dbc_wall(R"({"box_walls": {"min": [0, 0], "max": [0.4, 0.3], "open": ["-x", "+x", "+y"]}})", -1, "", model_json);
  s.make_stage(stage_json).compute_rates(s.world);
  const auto a = s.world.fluid.vector("acceleration");
  return {a.begin(), a.end()};
}

TEST(Mdbc, FreeSlipWallExertsNoDragOnAStreamAlongIt) {
  for (const char* viscosity : {R"({"viscosity": "laminar"})", R"({"viscosity": "artificial", "alpha": 0.1})"}) {
    const auto free_slip = drag(R"({"method": "mdbc", "slip": "free_slip"})", viscosity);
    const auto no_slip = drag(R"({"method": "mdbc"})", R"({"viscosity": "laminar"})");
    double largest_drag = 0.0;
    for (std::size_t i = 0; i < free_slip.size(); ++i) {
      EXPECT_NEAR(free_slip[i].x, 0.0, 1e-12) << viscosity;
      EXPECT_NEAR(free_slip[i].y, 0.0, 1e-9) << viscosity;
      largest_drag = std::max(largest_drag, -no_slip[i].x);
    }
    // The scale of the no-slip drag: nu u / dp^2 = 1e-6 * 0.01 / 0.02^2 = 2.5e-5 m/s^2.
    EXPECT_GT(largest_drag, 1e-5) << "the no-slip wall does drag the same stream";
  }
}

TEST(Mdbc, NoSlipDragEqualsTheMirroredDbcDragOfAUniformStream) {
  // A uniform stream: the ghost node's velocity and DBC's Shepard mean are both u exactly.
  const auto mdbc = drag(R"({"method": "mdbc"})", R"({"viscosity": "laminar"})");
  const auto dbc = drag(R"({"no_slip": "extrapolated"})", R"({"viscosity": "laminar"})");
  ASSERT_EQ(mdbc.size(), dbc.size());
  for (std::size_t i = 0; i < dbc.size(); ++i) EXPECT_NEAR(mdbc[i].x, dbc[i].x, 1e-9 * (1.0 + std::abs(dbc[i].x)));
}

TEST(Mdbc, FreeSlipNeedsMdbc) {
  EXPECT_THROW(talus::boundary::DynamicParticles(talus::params_from_json(
                   talus::boundary::DynamicParticles::describe(), R"({"slip": "free_slip"})", 2)),
               talus::InputError);
}

// Water at rest in a 2D tank on mDBC walls for 0.5 s.
TEST(Mdbc, TankOfWaterStaysAtRestWithTheFloorPressureOfItsDepth) {
  const double W = 0.4, H = 0.3, dp = 0.02, g = 9.81;
  SphWorld s(2, {0, 0, 0}, {W, H + 0.1, 0}, dp, 1.5);
  const int water = s.water(20.0 * std::sqrt(g * H));
  s.fluid_box(water, {0, 0, 0}, {W, H, 0}, true);
  s.dbc_wall(R"({"box_walls": {"min": [0, 0], "max": [0.4, 0.4], "open": ["+y"]}})", -1, "", R"({"method": "mdbc"})");
  s.make_stage(R"({"viscosity": "artificial", "alpha": 0.01, "density_diffusion": "fourtakas"})");
  while (s.world.time < 0.5) s.step();
  const auto x = s.world.fluid.position();
  const auto v = s.world.fluid.vector("velocity");
  const auto p = s.world.fluid.scalar("pressure");
  double v_max = 0.0, floor_pressure = 0.0, lowest = 1e300;
  int bottom = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    v_max = std::max(v_max, talus::norm(v[i]));
    lowest = std::min(lowest, x[i].y);
    if (x[i].y < dp && x[i].x > 0.1 && x[i].x < 0.3) {
      floor_pressure += p[i] + 1000.0 * g * x[i].y;  // the bottom row's pressure carried down to the floor
      ++bottom;
    }
  }
  ASSERT_GT(bottom, 0);
  floor_pressure /= bottom;
  EXPECT_LT(v_max, 0.01 * std::sqrt(g * H));
  EXPECT_NEAR(floor_pressure / (1000.0 * g * H), 1.0, 0.02);
  EXPECT_GT(lowest, 0.4 * dp) << "the bottom row stays half a spacing above the floor (no DBC gap, no sinking)";
  EXPECT_LT(lowest, 0.6 * dp);
}

}  // namespace
