// Mixed precision (the scene's "precision": "mixed"): the wcsph integrators
// keep the state they save from one stage or step to the next (Verlet's
// t^(n-1), the two-stage schemes' t^n) in float, and, where every reader of
// the fluid reads float (dynamic boundary particles do), the fluid's
// velocity, density, pressure, sound speed, mass and rates too; DBC walls
// keep their own fields in float. A 2D dam break with dynamic boundary
// particles then follows the run in double to within what rounding costs,
// and the fields are really in float (the runs differ).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

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
  FieldType velocity = FieldType::vector, density_type = FieldType::scalar, sound_speed = FieldType::scalar;
  FieldType acceleration = FieldType::vector, wall_density = FieldType::scalar;
};

// What is in float: nothing; the integrator's saved state; or every field
// that may be: the saved state, the fluid's own and the walls'.
enum class Single { none, saved_state, all };

// A 0.2 m x 0.4 m column collapsing in a 0.8 m x 0.5 m tank, dp = 0.01 m, for `steps` steps.
Run dam_break(const std::string& integrator, Single single, int steps) {
  // The fluid's own fields go to float only where the host allows it (SphWorld's Precision::mixed).
  SphWorld s(2, {0, 0, 0}, {0.8, 0.5, 0}, 0.01, 1.3, "wendland_c2",
             single == Single::all ? SphWorld::Precision::mixed : SphWorld::Precision::double_only);
  s.world.fluid.set_mixed_precision(single != Single::none);
  const int water = s.water(30.0);
  s.fluid_box(water, {0, 0, 0}, {0.2, 0.4, 0}, true);
  s.dbc_wall(R"({"box_walls": {"min": [0, 0], "max": [0.8, 0.5], "open": ["+y"]}})");
  s.make_stage(R"({"integrator": ")" + integrator + R"(", "density_diffusion": "fourtakas"})");
  for (int k = 0; k < steps; ++k) s.step();
  Run r;
  const auto& f = s.world.fluid;
  const auto id = f.ids();
  const auto x = f.position();
  std::vector<double> rho_wide, m_wide;
  const auto rho = f.scalar_in_double("density", rho_wide);
  const auto m = f.scalar_in_double("mass", m_wide);
  for (std::size_t i = 0; i < f.size(); ++i) {
    r.position[id[i]] = x[i];
    r.density[id[i]] = rho[i];
    r.mass += m[i];
  }
  r.saved_velocity = f.info(integrator == "verlet" ? "velocity_prev" : "velocity_n").type;
  r.velocity = f.info("velocity").type;
  r.density_type = f.info("density").type;
  r.sound_speed = f.info("sound_speed").type;
  r.acceleration = f.info("acceleration").type;
  r.wall_density = s.world.boundary.info("density").type;
  return r;
}

struct Differences {
  double position = 0.0;  // largest |x_mixed - x_double|, m
  double density = 0.0;   // largest |rho_mixed - rho_double| / rho_double
};

Differences largest_differences(const Run& d, const Run& m) {
  Differences worst;
  EXPECT_EQ(d.position.size(), m.position.size());
  for (const auto& [id, x] : d.position) {
    if (!m.position.count(id)) {
      ADD_FAILURE() << "particle " << id << " is missing in the mixed run";
      continue;
    }
    worst.position = std::max(worst.position, talus::norm(x - m.position.at(id)));
    worst.density = std::max(worst.density, std::abs(d.density.at(id) - m.density.at(id)) / d.density.at(id));
  }
  return worst;
}

constexpr double dp = 0.01;
constexpr int steps = 400;

// Each step rounds the saved velocity and density once, by at most 2^-24
// relative (half a float ulp). Added up over 400 steps with no cancellation
// that is 2.4e-5 of the density, the bound below; the positions move by
// velocity errors of that order times dt, far less than 1e-4 dp unless the
// flow amplifies them a hundredfold. A saved state that is lost, stale or read
// from the wrong row moves particles by a sizeable fraction of dp and changes
// the density by percents within these steps: the bounds tell the two apart.
void expect_follows_double(const std::string& integrator) {
  const Run d = dam_break(integrator, Single::none, steps), m = dam_break(integrator, Single::saved_state, steps);
  EXPECT_EQ(d.saved_velocity, FieldType::vector);
  EXPECT_EQ(m.saved_velocity, FieldType::vector_f32);
  EXPECT_EQ(m.velocity, FieldType::vector);  // a require() in double (SphWorld's) keeps the fluid's own in double
  EXPECT_EQ(d.mass, m.mass);
  const Differences worst = largest_differences(d, m);
  std::printf("%s, saved state in float, %d steps: largest position difference %.3g dp, density %.3g (relative)\n",
              integrator.c_str(), steps, worst.position / dp, worst.density);
  EXPECT_GT(worst.position, 0.0);  // the saved state is in float: the runs differ
  EXPECT_LT(worst.position, 1e-4 * dp);
  EXPECT_LT(worst.density, steps * std::ldexp(1.0, -24));
}

TEST(MixedPrecision, VerletStateInFloatFollowsTheDoubleRun) { expect_follows_double("verlet"); }
TEST(MixedPrecision, SymplecticStateInFloatFollowsTheDoubleRun) { expect_follows_double("symplectic"); }

// The fluid's velocity, density, pressure, sound speed, mass and rates, and
// the walls' fields, in float as well. The mass is rounded once, at the
// start: its sum moves by at most 2^-24 relative. Velocity and density are
// rounded once more per step or stage, pressure and sound speed once per EOS
// call, the rates once per pair they gather: the same kind of error as the
// saved state's, a few roundings a step instead of one, so the bounds are
// that test's, times 4. A field read from the wrong row or in the wrong type
// moves the particles by a fraction of dp within these steps.
void expect_all_in_float_follows_double(const std::string& integrator) {
  const Run d = dam_break(integrator, Single::none, steps), m = dam_break(integrator, Single::all, steps);
  EXPECT_EQ(m.velocity, FieldType::vector_f32);
  EXPECT_EQ(m.density_type, FieldType::scalar_f32);
  EXPECT_EQ(m.sound_speed, FieldType::scalar_f32);
  EXPECT_EQ(m.acceleration, FieldType::vector_f32);
  EXPECT_EQ(m.wall_density, FieldType::scalar_f32);
  EXPECT_EQ(m.saved_velocity, FieldType::vector_f32);
  EXPECT_NEAR(m.mass, d.mass, d.mass * std::ldexp(1.0, -24));
  const Differences worst = largest_differences(d, m);
  std::printf("%s, all in float, %d steps: largest position difference %.3g dp, density %.3g (relative)\n",
              integrator.c_str(), steps, worst.position / dp, worst.density);
  EXPECT_GT(worst.position, 0.0);
  EXPECT_LT(worst.position, 4e-4 * dp);
  EXPECT_LT(worst.density, 4 * steps * std::ldexp(1.0, -24));
}

TEST(MixedPrecision, VerletAllInFloatFollowsTheDoubleRun) { expect_all_in_float_follows_double("verlet"); }
TEST(MixedPrecision, SymplecticAllInFloatFollowsTheDoubleRun) { expect_all_in_float_follows_double("symplectic"); }

}  // namespace
