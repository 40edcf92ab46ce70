// Unit tests of the wcsph stage's pieces: momentum conservation of the
// symmetric force terms, the Fourtakas diffusion on a hydrostatic field,
// summation density, the time-step bound, the integrators on free fall, the
// dynamic boundary particles, the stage's input errors and its shared scratch.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <span>
#include <stdexcept>

#include "shared_scratch.hpp"
#include "sph_world.hpp"
#include "talus/error.hpp"
#include "talus/sph/neighbour_records.hpp"

namespace {

using sph_test::SphWorld;
using talus::Vec3;

// An isolated, disturbed fluid patch without gravity: the symmetric pressure
// and viscous terms conserve momentum, so sum_i m_i a_i = 0 to round-off.
void expect_momentum_conserved(int dim, const std::string& params) {
  SphWorld s(dim, {-1, -1, -1}, {1, 1, 1}, 0.05);
  s.world.gravity = {};
  const int water = s.water(20.0);
  s.fluid_box(water, {-0.3, -0.3, -0.3}, {0.3, 0.3, 0.3}, false);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  auto x = s.world.fluid.position();
  auto v = s.world.fluid.vector("velocity");
  auto rho = s.world.fluid.scalar("density");
  for (std::size_t i = 0; i < x.size(); ++i) {
    x[i] += Vec3{u(rng), u(rng), dim == 3 ? u(rng) : 0.0} * 0.01;
    v[i] = Vec3{u(rng), u(rng), dim == 3 ? u(rng) : 0.0};
    rho[i] = 1000.0 * (1.0 + 0.01 * u(rng));
  }
  auto& stage = s.make_stage(params);
  stage.compute_rates(s.world);
  const auto a = s.world.fluid.vector("acceleration");
  const auto m = s.world.fluid.scalar("mass");
  Vec3 total{};
  double scale = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    total += a[i] * m[i];
    scale += talus::norm(a[i]) * m[i];
  }
  ASSERT_GT(scale, 0.0);
  EXPECT_LT(talus::norm(total) / scale, 1e-12) << params << " in " << dim << "D";
  // The continuity equation conserves mass exactly too: sum_i m_i/rho_i drho_i ... is not a
  // conserved quantity, but the density rate of a pair is symmetric in v_ij: check finiteness.
  for (double d : s.world.fluid.scalar("density_rate")) ASSERT_TRUE(std::isfinite(d));
}

TEST(WcsphForces, MomentumConserved2D) {
  expect_momentum_conserved(2, R"({"viscosity": "artificial", "alpha": 0.1})");
  expect_momentum_conserved(2, R"({"viscosity": "artificial", "alpha": 0.0})");
}

TEST(WcsphForces, MomentumConserved3D) { expect_momentum_conserved(3, R"({"viscosity": "artificial", "alpha": 0.1})"); }

// A column in hydrostatic equilibrium (Tait density profile, fluid at rest):
// Molteni-Colagrossi diffusion acts on the hydrostatic density gradient,
// Fourtakas et al. (2019) removes it, and the continuity term is zero at rest.
TEST(WcsphDiffusion, FourtakasVanishesOnHydrostaticColumn) {
  for (int dim : {2, 3}) {
    auto max_rate = [&](const char* diffusion) {
      SphWorld s(dim, {0, 0, 0}, {0.4, 0.4, 0.4}, 0.02);
      const int water = s.water(20.0);
      // The column stands along -g: y in 2D, z in 3D.
      s.fluid_box(water, {0, 0, 0}, dim == 2 ? Vec3{0.2, 0.4, 0} : Vec3{0.2, 0.2, 0.4}, false);
      // Exact equilibrium dp/dz = -rho(p) g with Tait: integrating dp/rho(p) = g d gives
      // p(d) = B ((1 + (gamma-1)/gamma rho0 g d / B)^(gamma/(gamma-1)) - 1).
      const double B = 1000.0 * 400.0 / 7.0, top = 0.4;
      auto x = s.world.fluid.position();
      auto rho = s.world.fluid.scalar("density");
      for (std::size_t i = 0; i < x.size(); ++i) {
        const double depth = top - x[i][dim - 1];
        const double p = B * (std::pow(1.0 + 6.0 / 7.0 * 1000.0 * 9.81 * depth / B, 7.0 / 6.0) - 1.0);
        rho[i] = s.world.materials[water].eos->density_at(p);
      }
      auto& stage = s.make_stage(std::string(R"({"density_diffusion": ")") + diffusion + "\"}");
      stage.compute_rates(s.world);
      double r = 0.0;
      for (double d : s.world.fluid.scalar("density_rate")) r = std::max(r, std::abs(d));
      return r;
    };
    const double none = max_rate("none"), molteni = max_rate("molteni"), fourtakas = max_rate("fourtakas");
    EXPECT_EQ(none, 0.0) << dim << "D";
    EXPECT_GT(molteni, 1.0) << dim << "D";  // kg/m^3/s: clearly acting
    EXPECT_LT(fourtakas, 1e-4 * molteni) << dim << "D";
  }
}

// Summation density on a uniform lattice: uniform inside, equal to rho0 up to
// the kernel's lattice-sum error (about 1 % for Wendland C2 at h/dp = 1.3 in 2D).
TEST(WcsphDensity, SummationOnLatticeGivesRho0Inside) {
  SphWorld s(2, {0, 0, 0}, {1, 1, 0}, 0.02);
  s.world.gravity = {};
  const int water = s.water(20.0);
  s.fluid_box(water, {0, 0, 0}, {1, 1, 0}, false);
  auto& stage = s.make_stage(R"({"density": "summation"})");
  stage.compute_rates(s.world);
  const auto x = s.world.fluid.position();
  const auto rho = s.world.fluid.scalar("density");
  double lo = 1e9, hi = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i)
    if (x[i].x > 0.1 && x[i].x < 0.9 && x[i].y > 0.1 && x[i].y < 0.9) {
      lo = std::min(lo, rho[i]);
      hi = std::max(hi, rho[i]);
    }
  EXPECT_LT(hi - lo, 1e-9 * hi);
  EXPECT_NEAR(hi, 1000.0, 15.0);
}

// dt = C min(sqrt(h/|f|), h/(c0 + h visc)) at rest under gravity: the sound
// speed bound wins for c0 = 20 m/s, h = 0.026 m.
TEST(WcsphTimeStep, SoundSpeedBoundAtRest) {
  SphWorld s(2, {0, 0, 0}, {1, 1, 0}, 0.02);
  const int water = s.water(20.0);
  s.fluid_box(water, {0.4, 0.4, 0}, {0.6, 0.6, 0}, false);
  auto& stage = s.make_stage(R"({"courant": 0.25})");
  const double dt = stage.stable_time_step(s.world);
  const double h = 0.026;
  EXPECT_NEAR(dt, 0.25 * std::min(std::sqrt(h / 9.81), h / 20.0), 1e-12);
}

// A lone particle in free fall: symplectic, predictor-corrector and Verlet
// integrate constant acceleration exactly; Euler (semi-implicit) is first order.
TEST(WcsphIntegrators, FreeFall) {
  for (const char* integ : {"symplectic", "predictor_corrector", "verlet", "euler"}) {
    SphWorld s(2, {0, 0, 0}, {1, 10, 0}, 0.05);
    const int water = s.water(20.0);
    s.fluid_box(water, {0.5, 9.0, 0}, {0.55, 9.05, 0}, false, {0.3, 0.0, 0.0});
    ASSERT_EQ(s.world.fluid.size(), 1u);
    s.make_stage(std::string(R"({"integrator": ")") + integ + "\"}");
    const Vec3 x0 = s.world.fluid.position()[0];
    const double dt = 1e-3;
    for (int n = 0; n < 200; ++n) s.step(dt);
    const double t = s.world.time;
    const Vec3 x = s.world.fluid.position()[0];
    const Vec3 v = s.world.fluid.vector("velocity")[0];
    const double tol = std::string(integ) == "euler" ? 0.5 * 9.81 * t * dt * 1.01 : 1e-9;
    EXPECT_NEAR(x.y, x0.y - 0.5 * 9.81 * t * t, tol) << integ;
    EXPECT_NEAR(x.x, x0.x + 0.3 * t, 1e-12) << integ;
    EXPECT_NEAR(v.y, -9.81 * t, 1e-9) << integ;
  }
}

// Dynamic boundary particles: layers fill the kernel support, wall density
// never drops below rho0, and a hydrostatic start gives the bottom wall the
// fluid's pressure by extrapolation.
TEST(DynamicParticles, InitialWallPressureIsHydrostatic) {
  SphWorld s(2, {0, 0, 0}, {0.4, 0.4, 0}, 0.02);
  const int water = s.water(20.0);
  s.fluid_box(water, {0, 0, 0}, {0.4, 0.3, 0}, true);
  auto* wall = s.dbc_wall(R"({"box_walls": {"min": [0, 0], "max": [0.4, 0.4], "open": ["+y"]}})");
  EXPECT_GT(wall->count(), 0u);
  s.make_stage();
  const auto x = s.world.boundary.position();
  const auto p = s.world.boundary.scalar("pressure");
  const auto rho = s.world.boundary.scalar("density");
  double ymin = 1e9;
  for (const Vec3& q : x) ymin = std::min(ymin, q.y);
  EXPECT_NEAR(ymin, -0.05, 1e-9);  // 3 layers (support 2.6 dp) at -dp/2, -3dp/2, -5dp/2
  for (std::size_t b = 0; b < x.size(); ++b) {
    EXPECT_GE(rho[b], 1000.0);
    if (x[b].y < 0 && x[b].y > -0.02 && x[b].x > 0.1 && x[b].x < 0.3)  // first layer under the fluid
      EXPECT_NEAR(p[b], 1000.0 * 9.81 * (0.3 - x[b].y), 0.03 * 1000 * 9.81 * 0.3);
  }
}

// The seed's penalty force F = (K_s d - (v.n) K_d) n on one particle near a floor.
TEST(Repulsion, ForceLawOnOneParticle) {
  SphWorld s(2, {0, 0, 0}, {1, 1, 0}, 0.05);
  s.world.gravity = {};
  const int water = s.water(20.0);
  s.fluid_box(water, {0.5, 0.0, 0}, {0.55, 0.05, 0}, false, {0.0, -1.0, 0.0});  // one particle at y = 0.025
  ASSERT_EQ(s.world.fluid.size(), 1u);
  auto* wall = s.repulsion_wall(R"({"half_space": {"point": [0, 0], "normal": [0, 1]}})",
                                R"({"stiffness": 1000, "damping": 2, "distance": 0.04})");
  ASSERT_EQ(wall->planes().size(), 1u);
  auto& stage = s.make_stage();
  stage.compute_rates(s.world);
  const double m = s.world.fluid.scalar("mass")[0];
  const Vec3 a = s.world.fluid.vector("acceleration")[0];
  EXPECT_NEAR(a.y, (1000.0 * (0.04 - 0.025) + 1.0 * 2.0) / m, 1e-9);
  EXPECT_NEAR(a.x, 0.0, 1e-12);
  // 0.2 of the critical step of the damped spring, 2/w (sqrt(1 + z^2) - z).
  const double w = std::sqrt(1000.0 / m), z = 2.0 / (2.0 * std::sqrt(1000.0 * m));
  EXPECT_NEAR(wall->stable_time_step(s.world), 0.2 * 2.0 / w * (std::sqrt(1.0 + z * z) - z), 1e-12);
}

// The penalty spring only pushes: a particle leaving the layer faster than the
// spring pushes it (K_d v > K_s d) feels no force, and is not pulled back.
TEST(Repulsion, NeverPullsALeavingParticle) {
  SphWorld s(2, {0, 0, 0}, {1, 1, 0}, 0.05);
  s.world.gravity = {};
  const int water = s.water(20.0);
  s.fluid_box(water, {0.5, 0.0, 0}, {0.55, 0.05, 0}, false, {0.0, 10.0, 0.0});  // K_d v = 20 > K_s d = 15
  ASSERT_EQ(s.world.fluid.size(), 1u);
  s.repulsion_wall(R"({"half_space": {"point": [0, 0], "normal": [0, 1]}})",
                   R"({"stiffness": 1000, "damping": 2, "distance": 0.04})");
  auto& stage = s.make_stage();
  stage.compute_rates(s.world);
  EXPECT_EQ(s.world.fluid.vector("acceleration")[0].y, 0.0);
}

// A column held by repulsion walls (box_walls) stays in the tank.
TEST(Repulsion, HoldsAColumn) {
  SphWorld s(2, {0, 0, 0}, {0.2, 0.3, 0}, 0.01, 1.5);
  const int water = s.water(20.0);
  s.fluid_box(water, {0, 0, 0}, {0.2, 0.1, 0}, true);
  // K_s: the column's weight per particle (m g H/dp) over a fraction of dp.
  s.repulsion_wall(R"({"box_walls": {"min": [0, 0], "max": [0.2, 0.3], "open": ["+y"]}})",
                   R"({"stiffness": 2000, "damping": 0.5, "distance": 0.01})");
  s.make_stage();
  for (int n = 0; n < 2000; ++n) s.step();
  for (const Vec3& x : s.world.fluid.position()) {
    EXPECT_GT(x.y, 0.0);
    EXPECT_GT(x.x, 0.0);
    EXPECT_LT(x.x, 0.2);
  }
}

TEST(WcsphSetup, InputErrors) {
  {
    SphWorld s(2, {0, 0, 0}, {1, 1, 0}, 0.05);
    const int water = s.water(20.0);
    s.fluid_box(water, {0, 0, 0}, {0.2, 0.2, 0}, false);
    EXPECT_THROW(s.make_stage(R"({"viscosity": "laplacian"})"), talus::InputError);  // needs the muller kernel
    EXPECT_THROW(s.make_stage(R"({"viscosity": "laminar"})"), talus::InputError);    // needs a newtonian rheology
    EXPECT_THROW(s.make_stage(R"({"integrator": "rk4"})"), talus::InputError);
    EXPECT_THROW(s.make_stage(R"({"courant": 0})"), talus::InputError);
  }
  {
    SphWorld s(2, {0, 0, 0}, {1, 1, 0}, 0.05);
    const int water = s.water(20.0);
    s.fluid_box(water, {0, 0, 0}, {0.2, 0.2, 0}, false);
    s.world.materials[water].eos = nullptr;
    EXPECT_THROW(s.make_stage(), talus::InputError);
  }
}

}  // namespace

namespace pair_term_test {

// a_i += c sum_j m_j (x_i - x_j) W_ij through the SDK loop, as a pair-term plugin writes it.
struct Push {
  static constexpr bool uses_value = true, uses_gradient = false;
  const double* mass;
  double c;
  template <class S>
  void pair(const talus::sph::Pair& q, S& s) const {
    s.acc += q.dx * (c * mass[q.j] * q.w);
  }
};

class PushTerm final : public talus::sph::PairTerm {
 public:
  std::uint64_t add_rates(const talus::sph::PairTermInput& in) override {
    struct Sums {
      Vec3 acc;
    };
    auto start = [](talus::Index) { return Sums{}; };
    auto finish = [&](talus::Index i, const Sums& s) { in.rates.acceleration[i] += s.acc; };
    return talus::sph::fluid_pass(in, start, finish, Push{in.fluid.mass.data(), 3.0});
  }
  std::string pass_description() const override { return "push"; }
};

}  // namespace pair_term_test

// A pair term of the scene adds its rates after the stage's own passes, over
// exactly the neighbours within the kernel support (checked against a
// brute-force sum over all pairs), and, being antisymmetric, keeps momentum.
TEST(PairTerms, AddToTheRatesOverEveryNeighbour) {
  auto make = [](bool with_term, pair_term_test::PushTerm& term) {
    auto s = std::make_unique<SphWorld>(2, Vec3{0, 0, 0}, Vec3{1, 1, 0}, 0.02);
    const int water = s->water(20.0);
    s->fluid_box(water, {0.1, 0.1, 0}, {0.5, 0.3, 0}, true);
    if (with_term) s->world.pair_terms.push_back(&term);
    s->make_stage();
    s->stage->compute_rates(s->world);
    return s;
  };
  pair_term_test::PushTerm term;
  const auto plain = make(false, term);
  const auto pushed = make(true, term);
  EXPECT_TRUE(pushed->world.pair_terms_run);
  const auto x = pushed->world.fluid.position();
  const auto m = pushed->world.fluid.scalar("mass");
  const auto a0 = plain->world.fluid.vector("acceleration");
  const auto a1 = pushed->world.fluid.vector("acceleration");
  const talus::KernelTable& k = pushed->world.kernel;
  Vec3 momentum{};
  double largest = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    Vec3 expected{};
    for (std::size_t j = 0; j < x.size(); ++j) {
      const Vec3 dx = x[i] - x[j];
      const double r = norm(dx);
      if (j != i && r < k.support_radius()) expected += dx * (3.0 * m[j] * k.w(r));
    }
    const Vec3 added = a1[i] - a0[i];
    largest = std::max(largest, norm(expected));
    EXPECT_NEAR(norm(added - expected), 0.0, 1e-9 * (1.0 + norm(expected))) << "particle " << i;
    momentum += added * m[i];
  }
  EXPECT_GT(largest, 0.0);
  EXPECT_NEAR(norm(momentum), 0.0, 1e-12 * largest * m[0] * x.size());
  bool listed = false;
  for (const auto& pass : pushed->stage->plan(pushed->world).passes) listed = listed || pass == "pair term pass: push";
  EXPECT_TRUE(listed);
}

// The stage's shared scratch: one array at a time, aligned for the records,
// and a read as a type it no longer holds refused (passes out of order).
TEST(SharedScratch, HoldsOneArrayAtATime) {
  talus::wcsph::SharedScratch scratch;
  EXPECT_THROW(scratch.held<double>(), std::logic_error);  // nothing held yet
  const std::span<double> inv_rho = scratch.hold<double>(10);
  for (std::size_t i = 0; i < inv_rho.size(); ++i) inv_rho[i] = 1.0 / (1000.0 + static_cast<double>(i));
  EXPECT_EQ(scratch.held<double>().size(), 10u);
  EXPECT_EQ(scratch.held<double>()[3], 1.0 / 1003.0);
  EXPECT_THROW(scratch.held<float>(), std::logic_error);
  const std::span<talus::sph::NeighbourRecordDouble> records = scratch.hold<talus::sph::NeighbourRecordDouble>(7);
  EXPECT_EQ(records.size(), 7u);
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(records.data()) % talus::wcsph::SharedScratch::alignment, 0u);
  EXPECT_THROW(scratch.held<double>(), std::logic_error);  // the records took the 1/rho column's place
  EXPECT_EQ(scratch.held<talus::sph::NeighbourRecordDouble>().data(), records.data());
  EXPECT_EQ(scratch.hold<float>(0).size(), 0u);  // an empty array is held too
  EXPECT_NO_THROW(scratch.held<float>());
}
