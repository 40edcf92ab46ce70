// The run-out over curved terrain: the flow follows the surface without
// losing kinetic energy where the slope changes, the curvature enters the
// normal stress the friction sees, and Thacker's analytic oscillation in a
// parabolic canal is reproduced.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "talus/rheology.hpp"
#include "follow_surface.hpp"
#include "runout_world.hpp"

namespace talus::runout::test {
namespace {

constexpr double g = 9.81;
constexpr double rho = 2000.0;

// Total energy of the flow: kinetic (speed along the surface), potential of
// the base, and the depth-integrated hydrostatic energy 1/2 g cos(theta) h
// per unit mass.
struct Energy {
  double kinetic = 0.0, potential = 0.0, internal = 0.0;
  double total() const { return kinetic + potential + internal; }
};

// The energy at the end of the last step (the depth field is the one the
// step computed at its start, a step behind: its share is small).
Energy energy(const RunoutWorld& w) {
  const ParticleStore& s = w.world.fluid;
  auto pos = s.position();
  auto vol = s.scalar("volume");
  auto speed = s.scalar("speed");
  auto z = s.scalar("elevation");
  auto h = s.scalar("depth");
  Energy e;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const double m = rho * vol[i];
    const Vec3 gz = w.stage->terrain().gradient(pos[i].x, pos[i].y);
    e.kinetic += 0.5 * m * speed[i] * speed[i];
    e.potential += m * g * z[i];
    e.internal += 0.5 * m * g * h[i] / std::sqrt(1.0 + norm2(gz));
  }
  return e;
}

TEST(FollowSurface, KeepsTheSpeedAndEndsTangentToTheNewPlane) {
  const Vec3 v{3.0, -1.0, 0.0}, g0{-0.6, 0.1, 0.0}, g1{0.2, 0.3, 0.0};
  const double speed = std::sqrt(norm2(v) + std::pow(dot(g0, v), 2));
  const Vec3 w = follow_surface(v, g0, g1, speed);
  EXPECT_NEAR(std::sqrt(norm2(w) + std::pow(dot(g1, w), 2)), speed, 1e-12);
  // Same plane: unchanged.
  const Vec3 same = follow_surface(v, g0, g0, speed);
  EXPECT_NEAR(same.x, v.x, 1e-12);
  EXPECT_NEAR(same.y, v.y, 1e-12);
  // A 30 degree slope onto the flat: the plan speed grows by 1 / cos 30.
  const double t = std::tan(std::numbers::pi / 6);
  const Vec3 down{std::cos(std::numbers::pi / 6), 0.0, 0.0};
  const Vec3 flat = follow_surface(down, {-t, 0.0, 0.0}, {}, 1.0);
  EXPECT_NEAR(flat.x, 1.0, 1e-12);
}

// On a smooth surface one small step of follow_surface turns the plan
// velocity by the centripetal term of the plan equations of motion,
// dv = -cos^2(theta) grad Z (v.H.v) dt.
TEST(FollowSurface, OnASmoothSurfaceIsTheCurvatureTermOfTheEquationsOfMotion) {
  // Z = 0.3 x^2 + 0.2 x y - 0.1 y^2.
  const Hessian H{0.6, 0.2, -0.2};
  auto grad = [&](Vec3 x) { return Vec3{H.xx * x.x + H.xy * x.y, H.xy * x.x + H.yy * x.y, 0.0}; };
  const Vec3 x0{0.7, -0.4, 0.0}, v{2.0, 1.5, 0.0};
  const double dt = 1e-5;
  const Vec3 g0 = grad(x0);
  const double speed = std::sqrt(norm2(v) + std::pow(dot(g0, v), 2));
  const Vec3 turned = follow_surface(v, g0, grad(x0 + dt * v), speed);
  const double c2 = 1.0 / (1.0 + norm2(g0));
  const Vec3 expected = v - (c2 * along(H, v) * dt) * g0;
  const Vec3 dv = turned - v, dv_expected = expected - v;
  EXPECT_NEAR(dv.x, dv_expected.x, 1e-3 * std::abs(dv_expected.x));
  EXPECT_NEAR(dv.y, dv_expected.y, 1e-3 * std::abs(dv_expected.y));
}

// A frictionless strip released on a 30 degree slope runs onto the flat floor.
// Returns the energy balance once the whole mass is on the floor:
// (E - E0) / (kinetic energy then), and that kinetic energy over the potential
// energy lost.
struct SlopeToFloor {
  double energy_error = 0.0, kinetic_over_drop = 0.0;
};

SlopeToFloor slope_to_floor(double transition, double dp) {
  const double foot = 60.0, width = 8 * dp;
  RunoutWorld w({-5.0, 0.0, 0.0}, {400.0, width, 0.0}, dp, 1.3, {false, true, false});
  const int m = w.add_material("debris", rho, nullptr);
  w.fill_box({0.0, 0.0, 0.0}, {10.0, width, 0.0}, m);
  w.make_stage(R"({"terrain": {"plane_runout": {"slope": 30, "foot": 60, "transition_length": )" +
                   std::to_string(transition) + R"(}}, "release_thickness": 0.5})",
               60.0);
  const Energy e0 = energy(w);
  const double floor_start = foot + 0.5 * transition + 2.0 * w.world.h * 3.0;
  double t = 0.0;
  auto all_on_floor = [&] {
    for (const Vec3& p : w.world.fluid.position())
      if (p.x < floor_start) return false;
    return true;
  };
  while (!all_on_floor() && t < 30.0) {
    t += 0.1;
    w.run_to(t);
  }
  EXPECT_TRUE(all_on_floor()) << "the mass should reach the floor within 30 s";
  const Energy e = energy(w);
  SlopeToFloor r;
  r.energy_error = (e.total() - e0.total()) / e.kinetic;
  r.kinetic_over_drop = e.kinetic / (e0.potential - e.potential);
  std::printf("slope 30 deg to floor, transition %g m, dp %g: on the floor at t = %.1f s, kinetic / potential drop "
              "%.4f, energy error %.4f of the kinetic energy\n",
              transition, dp, t, r.kinetic_over_drop, r.energy_error);
  return r;
}

TEST(RunoutEnergy, SlopeToFloorThroughASmoothTransitionKeepsTheEnergy) {
  const SlopeToFloor r = slope_to_floor(60.0, 0.5);
  EXPECT_LT(std::abs(r.energy_error), 0.02);
  // Speed within 2 %: kinetic energy within 4 % of the drop (the rest is the
  // hydrostatic energy the strip spreads out of).
  EXPECT_GT(r.kinetic_over_drop, 0.96);
}

TEST(RunoutEnergy, SlopeToFloorOverASharpBreakKeepsTheEnergy) {
  const SlopeToFloor r = slope_to_floor(0.0, 0.5);
  EXPECT_LT(std::abs(r.energy_error), 0.02);
  EXPECT_GT(r.kinetic_over_drop, 0.96);
}

namespace fs = std::filesystem;

std::string temp_file(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / "talus_runout_energy";
  fs::create_directories(dir);
  return (dir / name).string();
}

// Thacker (1981, J. Fluid Mech. 107) in a parabolic canal Z = k y^2: a lens of
// vertical depth h = h0 (1 - (y - y_c)^2 / a^2), a = sqrt(h0 / k), that
// swings rigidly, y_c = -A cos(omega t), omega = sqrt(2 g k), at the uniform
// speed A omega sin(omega t). The canal runs along x (periodic strip).
struct Canal {
  double k, h0, amplitude;
  double a() const { return std::sqrt(h0 / k); }
  double omega() const { return std::sqrt(2.0 * g * k); }
  double period() const { return 2.0 * std::numbers::pi / omega(); }
  double centre(double t) const { return -amplitude * std::cos(omega() * t); }
  double depth(double y, double t) const {
    const double d = (y - centre(t)) / a();
    return std::max(0.0, h0 * (1.0 - d * d));
  }
};

// A run of the lens: the stage is set up from a thickness raster holding the
// slope-normal thickness h cos(theta) at every particle's position.
struct CanalRun {
  // Particles across the periodic strip: wider than the largest search radius (2 x 3 x 1.3 dp).
  static constexpr int strip = 12;
  RunoutWorld w;
  CanalRun(const Canal& c, double dp)
      : w({0.0, -c.amplitude - 2.0 * c.a(), 0.0}, {strip * dp, c.amplitude + 2.0 * c.a(), 0.0}, dp, 1.3,
          {true, false, false}) {
    const int m = w.add_material("water", rho, nullptr);
    const double y0 = c.centre(0.0) - c.a(), y1 = c.centre(0.0) + c.a();
    const double lo = w.world.lo.y + dp * std::floor((y0 - w.world.lo.y) / dp);
    w.fill_box({0.0, lo, 0.0}, {strip * dp, lo + dp * std::ceil((y1 - lo) / dp), 0.0}, m);
    // Raster cells centred on the particles.
    const int rows = static_cast<int>(std::lround((w.world.hi.y - w.world.lo.y) / dp));
    std::string text = "ncols " + std::to_string(strip) + "\nnrows " + std::to_string(rows) + "\nxllcorner 0\nyllcorner " +
                       std::to_string(w.world.lo.y) + "\ncellsize " + std::to_string(dp) + "\nNODATA_value -9999\n";
    for (int r = rows - 1; r >= 0; --r) {
      const double y = w.world.lo.y + (r + 0.5) * dp, slope = 2.0 * c.k * y;
      const double t = c.depth(y, 0.0) / std::sqrt(1.0 + slope * slope);
      for (int col = 0; col < strip; ++col) text += std::to_string(t) + (col < strip - 1 ? " " : "\n");
    }
    const std::string raster = temp_file("thacker_" + std::to_string(dp) + ".asc");
    std::ofstream(raster) << text;
    const double half = 0.5 * (w.world.hi.y - w.world.lo.y);
    w.make_stage(R"({"terrain": {"channel": {"slope": 0, "axis": 0, "half_width": )" + std::to_string(half) +
                     R"(, "bank_height": )" + std::to_string(c.k * half * half) + R"(}}, "thickness_raster": ")" +
                     raster + R"(", "depth_threshold": 0})",
                 1e9);
  }
};

// Relative L1 error of the vertical depth across the canal at time t.
double canal_error(const CanalRun& run, const Canal& c, double t) {
  double err = 0.0, ref = 0.0;
  const double dy = 0.05;
  for (double y = c.centre(t) - 1.5 * c.a(); y <= c.centre(t) + 1.5 * c.a(); y += dy) {
    const double exact = c.depth(y, t);
    err += std::abs(run.w.depth_at({2.0 * run.w.world.dp, y, 0.0}) - exact);  // cosine 1: the vertical depth
    ref += exact;
  }
  return err / ref;
}

// Gentle canal (slopes below 4 degrees, where the slope-normal model and the
// shallow-water equations of Thacker's solution agree to 0.2 %).
// Over the first half swing the error falls with resolution; over three
// periods it stays below 0.5 % at every resolution (the particle noise the
// artificial viscosity damps sets it there at the finest, not the swing).
TEST(ThackerCanal, LensSwingsAsTheAnalyticSolutionAndConvergesWithResolution) {
  const Canal c{1e-4, 0.05, 0.5 * std::sqrt(0.05 / 1e-4)};
  double previous = 1.0;
  for (const double dp : {1.0, 0.5, 0.25}) {
    CanalRun run(c, dp);
    const double T = c.period();
    double early = 0.0, late = 0.0;
    for (const double t : {0.25 * T, 0.5 * T, T, 2.0 * T, 3.0 * T}) {
      run.w.run_to(t);
      const double e = canal_error(run, c, t);
      (t <= 0.5 * T ? early : late) = std::max(t <= 0.5 * T ? early : late, e);
      std::printf("Thacker canal dp %g (a/%.0f): t = %.2f T, L1 %.4f\n", dp, c.a() / dp, t / T, e);
    }
    EXPECT_LT(early, previous) << "dp " << dp;
    EXPECT_LT(late, 0.005) << "dp " << dp;
    previous = early;
  }
  EXPECT_LT(previous, 0.001);
}

// A steep canal (the lens climbs to 28 degrees): the mass swings across it
// for four periods; frictionless, its total energy must stay constant.
TEST(ValleyOscillation, FrictionlessMassKeepsItsEnergyOverSeveralPeriods) {
  const Canal c{0.01, 0.5, 20.0};
  for (const double dp : {0.5, 0.25}) {
    CanalRun run(c, dp);
    const Energy e0 = energy(run.w);
    const double T = c.period();
    double worst = 0.0, swing = 0.0;
    for (double t = 0.05 * T; t <= 4.0 * T + 1e-9; t += 0.05 * T) {
      run.w.run_to(t);
      const Energy e = energy(run.w);
      worst = std::max(worst, std::abs(e.total() - e0.total()));
      swing = std::max(swing, e.kinetic);
    }
    std::printf("steep canal dp %g: largest energy error over 4 periods %.5f of the largest kinetic energy\n", dp,
                worst / swing);
    EXPECT_LT(worst / swing, 0.01) << "dp " << dp;

  }
}

// A frictionless "rheology" that records the normal load g_n the stage
// passes to the basal law.
struct LoadProbe final : Rheology {
  mutable std::vector<double> load;
  bool has_basal_shear() const override { return true; }
  void basal_shear(std::span<const Index> idx, const BasalInputs& in, double* tau) const override {
    for (const Index i : idx) {
      if (load.size() <= static_cast<std::size_t>(i)) load.resize(i + 1);
      load[i] = in.normal_gravity[i];
      tau[i] = 0.0;
    }
  }
};

// Through the concave 30 degree -> flat transition (curvature tan 30 / L) the
// basal law sees g_n = cos(theta) (g + v.H.v), not g cos(theta).
TEST(CurvatureLoad, ConcaveBendAddsTheCentrifugalLoad) {
  const double dp = 0.5, width = 8 * dp, L = 60.0, foot = 60.0;
  RunoutWorld w({-5.0, 0.0, 0.0}, {300.0, width, 0.0}, dp, 1.3, {false, true, false});
  auto probe = std::make_unique<LoadProbe>();
  const LoadProbe* rec = probe.get();
  const int m = w.add_material("debris", rho, std::move(probe));
  w.fill_box({0.0, 0.0, 0.0}, {10.0, width, 0.0}, m);
  w.make_stage(R"({"terrain": {"plane_runout": {"slope": 30, "foot": 60, "transition_length": 60}}, )"
               R"("release_thickness": 0.5})",
               60.0);
  const double s = std::tan(30.0 * std::numbers::pi / 180.0), curvature = s / L;
  int checked = 0;
  double largest = 0.0;
  for (double t = 0.5; t < 8.0; t += 0.5) {
    w.run_to(t);
    auto pos = w.world.fluid.position();
    auto vel = w.world.fluid.vector("velocity");
    for (std::size_t i = 0; i < pos.size(); ++i) {
      if (pos[i].x < foot - 0.5 * L + 2.0 || pos[i].x > foot + 0.5 * L - 2.0) continue;
      const Vec3 gz = w.stage->terrain().gradient(pos[i].x, pos[i].y);
      const double c = 1.0 / std::sqrt(1.0 + norm2(gz));
      const double expected = c * (g + curvature * vel[i].x * vel[i].x);
      // The load is taken after this step's first kick, the velocity here at its end: O(dt) apart.
      EXPECT_NEAR(rec->load[i], expected, 0.02 * expected) << "particle " << i << " at x = " << pos[i].x;
      largest = std::max(largest, rec->load[i] / (g * c));
      ++checked;
    }
  }
  EXPECT_GT(checked, 100);
  std::printf("concave bend: largest g_n / (g cos theta) %.3f\n", largest);
  EXPECT_GT(largest, 1.2);
}

// Over a convex edge taken faster than sqrt(g R) the flow would leave the
// ground: the load is clamped at zero (no friction), the particle-steps are
// counted, and the flow keeps following the surface.
TEST(CurvatureLoad, ConvexEdgeTakenFastGivesZeroLoadAndIsCounted) {
  const double dp = 0.5, width = 8 * dp, R = 20.0, cell = 1.0;
  // DEM: flat at 100 m to x = 50, then a convex arc of radius R into a 30 degree slope.
  const double s = std::tan(30.0 * std::numbers::pi / 180.0), x1 = 50.0 + R * s;
  auto z = [&](double x) {
    if (x <= 50.0) return 100.0;
    if (x <= x1) return 100.0 - (x - 50.0) * (x - 50.0) / (2.0 * R);
    return 100.0 - R * s * s / 2.0 - s * (x - x1);
  };
  const int cols = 200, rows = 10;
  std::string text = "ncols " + std::to_string(cols) + "\nnrows " + std::to_string(rows) +
                     "\nxllcorner -20\nyllcorner -3\ncellsize 1\n";
  for (int r = 0; r < rows; ++r)
    for (int col = 0; col < cols; ++col) text += std::to_string(z(-20.0 + (col + 0.5) * cell)) + (col < cols - 1 ? " " : "\n");
  const std::string dem = temp_file("convex_edge.asc");
  std::ofstream(dem) << text;
  RunoutWorld w({-15.0, 0.0, 0.0}, {175.0, width, 0.0}, dp, 1.3, {false, true, false});
  auto probe = std::make_unique<LoadProbe>();
  const LoadProbe* rec = probe.get();
  const int m = w.add_material("debris", rho, std::move(probe));
  w.fill_box({20.0, 0.0, 0.0}, {30.0, width, 0.0}, m, {25.0, 0.0, 0.0});
  w.make_stage(R"({"terrain": {"dem": {"file": ")" + dem + R"("}}, "release_thickness": 0.2})", 10.0);
  int zero_load = 0;
  for (double t = 0.05; t < 2.0; t += 0.05) {
    w.run_to(t);
    auto pos = w.world.fluid.position();
    for (std::size_t i = 0; i < pos.size(); ++i)
      if (pos[i].x > 52.0 && pos[i].x < x1 - 2.0 && rec->load[i] == 0.0) ++zero_load;
  }
  std::printf("convex edge at 25 m/s (R = %g m): %llu particle-steps without basal contact\n", R,
              static_cast<unsigned long long>(w.stage->lifted_particle_steps()));
  EXPECT_GT(zero_load, 0);
  EXPECT_GT(w.stage->lifted_particle_steps(), 0u);
  EXPECT_NE(w.stage->status(w.world).find("no basal contact"), std::string::npos) << w.stage->status(w.world);
  for (const Vec3& p : w.world.fluid.position()) EXPECT_GT(p.x, x1) << "the whole mass should be past the edge";
}

}  // namespace
}  // namespace talus::runout::test
