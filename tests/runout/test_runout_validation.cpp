// Validation of the depth-integrated SPH stage against analytic solutions:
// Ritter's dry-bed dam break, Mangeney's Coulomb dam break on an incline,
// Voellmy steady flow, Coulomb start/stop and mass conservation.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "analytic.hpp"
#include "coulomb.hpp"
#include "runout_world.hpp"
#include "voellmy.hpp"

namespace talus::runout::test {
namespace {

constexpr double g = 9.81;
constexpr double deg = std::numbers::pi / 180.0;

std::unique_ptr<Rheology> coulomb(double delta_deg) {
  return std::make_unique<rheology::Coulomb>(params_from_json(
      rheology::Coulomb::describe(), R"({"friction_angle": )" + std::to_string(delta_deg) + "}"));
}

struct DamBreakResult {
  double l1 = 0.0;     // relative L1 error of the depth profile
  double front = 0.0;  // the front: the furthest particle (along the slope)
  double front_l = 0.0;  // its smoothing length (along the slope)
  double front_volume = 0.0;  // its volume per unit width (integral of h along the flow)
};

// A quasi-1D dam break spreads along x only, so the smoothing length follows
// the particle spacing along x: the "depth" law. Its bound (50 h) is never
// reached, so the front particle's l is the honest local resolution there.
// The strip is periodic across y.
constexpr const char* strip_smoothing = R"("smoothing_law": "depth", "max_smoothing_ratio": 50, "depth_threshold": 0)";

// Depth profile error on [s0, s1] (along the slope) and the front, for a
// strip over a plane of cosine c.
template <class Exact>
DamBreakResult compare(const RunoutWorld& w, double width, double c, double s0, double s1, Exact exact) {
  DamBreakResult r;
  double err = 0.0, ref = 0.0;
  for (double s = s0; s <= s1; s += 0.01) {
    const double e = exact(s);
    err += std::abs(w.depth_at({s * c, 0.5 * width, 0.0}, c) - e);
    ref += e;
  }
  r.l1 = err / ref;
  auto pos = w.world.fluid.position();
  auto ell = w.world.fluid.scalar("smoothing_length");
  auto vol = w.world.fluid.scalar("volume");
  std::size_t lead = 0;
  for (std::size_t i = 0; i < pos.size(); ++i)
    if (pos[i].x > pos[lead].x) lead = i;
  r.front = pos[lead].x / c;
  r.front_l = ell[lead] / c;
  r.front_volume = vol[lead] / w.world.dp;
  return r;
}

// The front criterion of the issue: the furthest particle within two of its
// smoothing lengths of the analytic front. The gap is not an error of the
// dynamics: the exact profile holds only (s_f - s)^3 / (27 g t^2) of volume
// near the front, so one particle's volume sits about cbrt(V) behind it. The
// dynamics are checked separately: the leading particle must be where the
// exact solution puts the middle of its volume (within l / 4).
void expect_front(const char* name, const DamBreakResult& r, double exact_front, double exact_lead) {
  std::printf("%s: front (furthest particle) %.3f m, exact %.3f m, gap %.3f m = %.2f l (l %.3f m); "
              "exact position of its volume %.3f m (off by %.3f l)\n",
              name, r.front, exact_front, exact_front - r.front, (exact_front - r.front) / r.front_l, r.front_l,
              exact_lead, (r.front - exact_lead) / r.front_l);
  EXPECT_NEAR(r.front, exact_front, 2.0 * r.front_l) << name;
  EXPECT_NEAR(r.front, exact_lead, 0.25 * r.front_l) << name;
}

// Ritter: frictionless flat bed, reservoir of depth 1 m on [-7, 0]; compared
// at t sqrt(g / h0) = 2 on x in [-2, 5] (the rarefaction head is at -2).
DamBreakResult ritter(double dp) {
  const double h0 = 1.0, width = 60 * dp;
  RunoutWorld w({-8.0, 0.0, 0.0}, {8.0, width, 0.0}, dp, 1.3, {false, true, false});
  const int m = w.add_material("water", 1000.0, nullptr);
  w.fill_box({-7.0, 0.0, 0.0}, {0.0, width, 0.0}, m);
  const double t = 2.0 / std::sqrt(g / h0);
  w.make_stage(std::string(R"({"terrain": {"plane": {"slope": 0}}, "release_thickness": 1.0, )") + strip_smoothing + "}",
               t);
  w.run_to(t);
  return compare(w, width, 1.0, -2.0, 5.0, [&](double x) { return ritter_depth(x, t, h0, g); });
}

TEST(RitterDamBreak, DepthProfileAndFrontMatchAndErrorFallsWithResolution) {
  const DamBreakResult coarse = ritter(0.2);
  const DamBreakResult fine = ritter(0.1);
  const double t = 2.0 / std::sqrt(g), front = 2.0 * std::sqrt(g * 1.0) * t;  // = 4 h0
  std::printf("Ritter: L1 %.4f (dp 0.2), %.4f (dp 0.1)\n", coarse.l1, fine.l1);
  EXPECT_LT(fine.l1, 0.05);
  EXPECT_LT(fine.l1, coarse.l1);
  expect_front("Ritter dp 0.2", coarse, front, dam_break_position(0.5 * coarse.front_volume, t, 1.0, g));
  expect_front("Ritter dp 0.1", fine, front, dam_break_position(0.5 * fine.front_volume, t, 1.0, g));
}

// Mangeney: 30 deg plane, delta = 20 deg, h0 = 1 m (slope-normal) on s in
// [-8, 0]; front at 6.736 m after 1 s; profile compared on s in [-2, 7.5].
TEST(MangeneyDamBreak, CoulombDamBreakOnInclineMatchesAnalyticSolution) {
  const double theta = 30.0 * deg, delta = 20.0 * deg, h0 = 1.0, t = 1.0, dp = 0.1;
  const double c = std::cos(theta), width = 60 * dp;
  RunoutWorld w({-8.0, 0.0, 0.0}, {9.0, width, 0.0}, dp, 1.3, {false, true, false});
  const int m = w.add_material("granular", 2000.0, coulomb(20.0));
  w.fill_box({-8.0 * c, 0.0, 0.0}, {0.0, width, 0.0}, m);
  w.make_stage(std::string(R"({"terrain": {"plane": {"slope": 30}}, "release_thickness": 1.0, )") + strip_smoothing + "}",
               t);
  w.run_to(t);
  const DamBreakResult r =
      compare(w, width, c, -2.0, 7.5, [&](double s) { return mangeney_depth(s, t, h0, g, theta, delta); });
  const double exact_front = mangeney_front(t, h0, g, theta, delta);
  std::printf("Mangeney: L1 %.4f\n", r.l1);
  EXPECT_NEAR(exact_front, 6.736, 1e-3);
  EXPECT_LT(r.l1, 0.05);
  const double gn = g * c, shift = 0.5 * (g * std::sin(theta) - gn * std::tan(delta)) * t * t;
  // The volume per unit width along the slope: V / dp in plan is h ds (slope-normal h, ds = dx / c).
  expect_front("Mangeney", r, exact_front, dam_break_position(0.5 * r.front_volume, t, h0, gn, shift));
  for (const double d : w.world.fluid.scalar("depth")) ASSERT_TRUE(std::isfinite(d) && d > 0.0);
}

// Voellmy: an infinite uniform layer (periodic both ways) of slope-normal
// depth 1 m on 30 deg reaches v = sqrt(xi h (sin theta - mu cos theta)).
TEST(VoellmySteadyFlow, SpeedMatchesInfiniteSlopeValue) {
  const double dp = 0.25, theta = 30.0 * deg;
  RunoutWorld w({0.0, 0.0, 0.0}, {12 * dp, 12 * dp, 0.0}, dp, 1.3, {true, true, false});
  const int m = w.add_material("debris", 2000.0,
                               std::make_unique<rheology::Voellmy>(params_from_json(
                                   rheology::Voellmy::describe(), R"({"friction_coefficient": 0.2, "turbulence": 500})")));
  w.fill_box({0.0, 0.0, 0.0}, {12 * dp, 12 * dp, 0.0}, m);
  w.make_stage(R"({"terrain": {"plane": {"slope": 30}}, "release_thickness": 1.0})", 30.0);
  w.run_to(30.0);
  double speed = 0.0, depth = 0.0;
  for (const double v : w.world.fluid.scalar("speed")) speed += v;
  for (const double h : w.world.fluid.scalar("depth")) depth += h;
  speed /= w.world.fluid.size();
  depth /= w.world.fluid.size();
  const double exact = std::sqrt(500.0 * 1.0 * (std::sin(theta) - 0.2 * std::cos(theta)));
  std::printf("Voellmy: speed %.4f m/s (exact %.4f), depth %.5f m\n", speed, exact, depth);
  EXPECT_NEAR(exact, 12.783, 1e-3);
  EXPECT_NEAR(speed, exact, 0.01 * exact);
}

// A frictional layer on a slope gentler than its friction angle never moves.
TEST(CoulombStart, MassOnSlopeGentlerThanFrictionAngleDoesNotStart) {
  const double dp = 0.2;
  RunoutWorld w({0.0, 0.0, 0.0}, {12 * dp, 12 * dp, 0.0}, dp, 1.3, {true, true, false});
  const int m = w.add_material("sand", 1900.0, coulomb(30.0));
  w.fill_box({0.0, 0.0, 0.0}, {12 * dp, 12 * dp, 0.0}, m);
  w.make_stage(R"({"terrain": {"plane": {"slope": 20}}, "release_thickness": 2.0})", 2.0);
  const std::vector<Vec3> start(w.world.fluid.position().begin(), w.world.fluid.position().end());
  const int steps = w.run_to(2.0);
  EXPECT_GT(steps, 10);
  auto pos = w.world.fluid.position();
  for (std::size_t i = 0; i < pos.size(); ++i) {
    ASSERT_EQ(w.world.fluid.vector("velocity")[i], (Vec3{})) << "particle " << i;
    ASSERT_EQ(pos[i], start[i]) << "particle " << i;
  }
}

// Released on a 35 deg slope with delta = 25 deg, the mass runs onto the
// flat zone, stops, and then stays exactly where it stopped; volume is
// conserved exactly and the deposit raster holds it.
void stops_and_stays(double transition_length) {
  const double dp = 0.1;
  RunoutWorld w({-8.0, -5.0, 0.0}, {10.0, 5.0, 0.0}, dp);
  const int m = w.add_material("sand", 1900.0, coulomb(25.0));
  w.fill_box({-6.0, -1.0, 0.0}, {-4.0, 1.0, 0.0}, m);
  w.make_stage(R"({"terrain": {"plane_runout": {"slope": 35, "foot": 0, "transition_length": )" +
                   std::to_string(transition_length) + R"(}}, "release_thickness": 0.5, "raster_cell": 0.1})",
               12.0);
  const double volume0 = w.stage->total_volume(w.world);
  const std::size_t count0 = w.world.fluid.size();
  w.run_to(9.0);
  for (const double v : w.world.fluid.scalar("speed")) ASSERT_EQ(v, 0.0);
  const std::vector<Vec3> stopped(w.world.fluid.position().begin(), w.world.fluid.position().end());
  w.run_to(12.0);
  auto pos = w.world.fluid.position();
  for (std::size_t i = 0; i < pos.size(); ++i) ASSERT_EQ(pos[i], stopped[i]) << "particle " << i << " crept";
  EXPECT_GT(w.max_x(), 0.0) << "the mass should reach the run-out zone";
  EXPECT_EQ(w.world.fluid.size(), count0);
  EXPECT_EQ(w.stage->total_volume(w.world), volume0);
  double mass = 0.0;
  for (const double x : w.world.fluid.scalar("mass")) mass += x;
  EXPECT_NEAR(mass, 1900.0 * volume0, 1e-9 * mass);
  // The final thickness raster integrates to the released volume (the
  // raster is vertical-column based: thickness / cos on the slope).
  const Grid& dep = w.stage->rasters().deposit_thickness();
  double raster_volume = 0.0;
  for (int r = 0; r < dep.nrows; ++r)
    for (int c = 0; c < dep.ncols; ++c) {
      const Vec3 gz = w.stage->terrain().gradient(dep.x_of(c), dep.y_of(r));
      raster_volume += dep.at(c, r) * std::sqrt(1.0 + norm2(gz)) * dep.cell * dep.cell;
    }
  std::printf("tilted-then-flat (L = %g): run-out %.3f m, volume %.4f m3, raster %.4f m3\n", transition_length,
              w.stage->runout_distance(), volume0, raster_volume);
  EXPECT_NEAR(raster_volume, volume0, 0.01 * volume0);
}

TEST(CoulombStop, TiltedThenFlatSharpBreakStopsAndStaysStopped) { stops_and_stays(0.0); }
TEST(CoulombStop, TiltedThenFlatSmoothBreakStopsAndStaysStopped) { stops_and_stays(2.0); }

}  // namespace
}  // namespace talus::runout::test
