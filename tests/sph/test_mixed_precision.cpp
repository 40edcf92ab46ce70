// Mixed precision (the scene's "precision": "mixed"): the wcsph integrators
// keep the state they save from one stage or step to the next (Verlet's
// t^(n-1), the two-stage schemes' t^n) in float. A 2D dam break with dynamic
// boundary particles then follows the run in double to within what rounding
// that state costs, and the state is really in float (the runs differ).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "sph_world.hpp"

namespace {

using sph_test::SphWorld;
using talus::FieldType;
using talus::Vec3;

struct Run {
  std::map<std::uint64_t, Vec3> position;  // by id: the re-sort reorders the rows
  std::map<std::uint64_t, double> density;
  double mass = 0.0;
  FieldType saved_velocity = FieldType::vector;
};

// A 0.2 m x 0.4 m column collapsing in a 0.8 m x 0.5 m tank, dp = 0.01 m, for `steps` steps.
Run dam_break(const std::string& integrator, bool mixed, int steps) {
  SphWorld s(2, {0, 0, 0}, {0.8, 0.5, 0}, 0.01);
  s.world.fluid.set_mixed_precision(mixed);
  s.world.boundary.set_mixed_precision(mixed);
  const int water = s.water(30.0);
  s.fluid_box(water, {0, 0, 0}, {0.2, 0.4, 0}, true);
  s.dbc_wall(R"({"box_walls": {"min": [0, 0], "max": [0.8, 0.5], "open": ["+y"]}})");
  s.make_stage(R"({"integrator": ")" + integrator + R"(", "density_diffusion": "fourtakas"})");
  for (int k = 0; k < steps; ++k) s.step();
  Run r;
  const auto& f = s.world.fluid;
  const auto id = f.ids();
  const auto x = f.position();
  const auto rho = f.scalar("density");
  const auto m = f.scalar("mass");
  for (std::size_t i = 0; i < f.size(); ++i) {
    r.position[id[i]] = x[i];
    r.density[id[i]] = rho[i];
    r.mass += m[i];
  }
  r.saved_velocity = f.info(integrator == "verlet" ? "velocity_prev" : "velocity_n").type;
  return r;
}

// Each step rounds the saved velocity and density once, by at most 2^-24
// relative (half a float ulp). Added up over 400 steps with no cancellation
// that is 2.4e-5 of the density, the bound below; the positions move by
// velocity errors of that order times dt, far less than 1e-4 dp unless the
// flow amplifies them a hundredfold. A saved state that is lost, stale or read
// from the wrong row moves particles by a sizeable fraction of dp and changes
// the density by percents within these steps: the bounds tell the two apart.
void expect_follows_double(const std::string& integrator) {
  const int steps = 400;
  const Run d = dam_break(integrator, false, steps), m = dam_break(integrator, true, steps);
  EXPECT_EQ(d.saved_velocity, FieldType::vector);
  EXPECT_EQ(m.saved_velocity, FieldType::vector_f32);
  ASSERT_EQ(d.position.size(), m.position.size());
  EXPECT_EQ(d.mass, m.mass);
  double worst_x = 0.0, worst_rho = 0.0;
  for (const auto& [id, x] : d.position) {
    ASSERT_TRUE(m.position.count(id)) << id;
    worst_x = std::max(worst_x, talus::norm(x - m.position.at(id)));
    worst_rho = std::max(worst_rho, std::abs(d.density.at(id) - m.density.at(id)) / d.density.at(id));
  }
  const double dp = 0.01;
  std::printf("%s, %d steps: largest position difference %.3g dp, density %.3g (relative)\n", integrator.c_str(),
              steps, worst_x / dp, worst_rho);
  EXPECT_GT(worst_x, 0.0);  // the saved state is in float: the runs differ
  EXPECT_LT(worst_x, 1e-4 * dp);
  EXPECT_LT(worst_rho, steps * std::ldexp(1.0, -24));
}

TEST(MixedPrecision, VerletStateInFloatFollowsTheDoubleRun) { expect_follows_double("verlet"); }
TEST(MixedPrecision, SymplecticStateInFloatFollowsTheDoubleRun) { expect_follows_double("symplectic"); }

}  // namespace
