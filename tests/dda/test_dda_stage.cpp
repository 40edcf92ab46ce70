// The dda stage on small scenes with analytic answers: free fall, a block on
// an incline (sliding and at rest), sliding versus toppling (Hoek & Bray),
// bounce with bounded energy, a stack at rest, bonded joints, prescribed
// motion and sub-cycling.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "dda_test_world.hpp"
#include "talus/error.hpp"

using namespace talus;
using namespace talus::dda;
using talus::dda::test::BlockScene;
using talus::dda::test::block;
using talus::dda::test::box;
using talus::dda::test::contact;
using talus::dda::test::rotated_box_json;

namespace {

constexpr double g = 9.81;
constexpr double deg = std::numbers::pi / 180.0;

// A 0.2 m cube on a slab inclined at theta (descending along +x), both
// rotated about the origin; the slab's joint has friction angle phi.
struct Incline {
  BlockScene scene;
  Vec3 start{}, down{};
  Incline(double theta, double phi) {
    scene.add_block(block("slope", rotated_box_json({-1, -0.5, -0.2}, {3, 0.5, 0}, theta, {0, 0, 0}),
                          ", \"fixed\": true"),
                    contact(phi));
    scene.add_block(block("cube", rotated_box_json({0, -0.1, 0}, {0.2, 0.1, 0.2}, theta, {0, 0, 0})), contact(phi));
    scene.start();
    start = scene.blocks().position[1];
    down = {std::cos(theta * deg), 0.0, -std::sin(theta * deg)};
  }
  double travelled() { return dot(scene.blocks().position[1] - start, down); }
};

}  // namespace

TEST(DdaStage, FreeFallIsExactForConstantGravity) {
  BlockScene s;
  s.add_block(block("rock", box({0, 0, 0}, {1, 1, 1}), ", \"velocity\": [1, 0, 2]"), contact(30));
  auto& stage = s.start();
  EXPECT_TRUE(std::isfinite(stage.own_time_step()));
  s.run_steps(1000, 1e-3);
  const Vec3 x = s.blocks().position[0];
  EXPECT_NEAR(x.x, 0.5 + 1.0, 1e-12);
  EXPECT_NEAR(x.z, 0.5 + 2.0 - 0.5 * g, 1e-9);
  EXPECT_NEAR(s.blocks().mass[0], 2500.0, 1e-9);
  // Energy: kinetic + potential stays at its initial value (the leapfrog's
  // synchronous kinetic energy makes this exact for constant forces, but
  // for the half-kick start: m g^2 dt^2 / 8).
  const auto& e = s.blocks().energy;
  const double e0 = 0.5 * 2500 * 5.0 - 2500 * (-g) * 0.5;
  EXPECT_NEAR((e.kinetic + e.potential) / e0, 1.0, 1e-6);  // O(g^2 dt^2) from the half-kick start
}

TEST(DdaStage, TorqueFreeSpinKeepsAngularMomentum) {
  BlockScene s({0, 0, 0});
  s.add_block(block("spinner", box({0, 0, 0}, {1, 2, 3}), ", \"angular_velocity\": [0.3, 2.0, 0.05]"), contact(30));
  s.start();
  const auto I0 = s.blocks().inertia[0];
  const Vec3 w0 = s.blocks().angular_velocity[0];
  const Vec3 L0{I0[0] * w0.x, I0[4] * w0.y, I0[8] * w0.z};
  const double e0 = 0.5 * dot(w0, L0);
  s.run_steps(2000, 1e-3);
  // L = R I_body R^T w is conserved; the reported w is the mid-step one and
  // the orientation the end-of-step one, so they agree to O(|w| dt) = 2e-3.
  const auto& b = s.blocks();
  const Vec3 wb = rotate_inverse(b.orientation[0], b.angular_velocity[0]);
  const Vec3 L = rotate(b.orientation[0], Vec3{I0[0] * wb.x, I0[4] * wb.y, I0[8] * wb.z});
  EXPECT_NEAR(norm(L - L0) / norm(L0), 0.0, 2e-3);
  EXPECT_NEAR(b.energy.kinetic / e0, 1.0, 1e-3);
}

TEST(DdaStage, BlockSlidesDownAnInclineAsCoulombPredicts) {
  // theta = 30 deg, phi = 20 deg: a = g (sin 30 - cos 30 tan 20) = 1.813 m/s^2, d(1 s) = 0.906 m.
  Incline inc(30.0, 20.0);
  inc.scene.run_until(1.0);
  const double a = g * (std::sin(30 * deg) - std::cos(30 * deg) * std::tan(20 * deg));
  EXPECT_NEAR(a, 1.813, 1e-3);
  const double expected = 0.5 * a;
  EXPECT_NEAR(inc.travelled() / expected, 1.0, 0.01) << "travelled " << inc.travelled() << " m";
  std::printf("incline 30/20: travelled %.6f m in 1 s, analytic %.6f m, error %.3g %%\n", inc.travelled(), expected,
              100.0 * (inc.travelled() / expected - 1.0));
  // It slides, it does not tumble.
  const Quaternion q = inc.scene.blocks().orientation[1];
  EXPECT_NEAR(std::abs(q.w), 1.0, 1e-6);
  // Half-way check of the t^2 law.
  EXPECT_GT(inc.scene.stage->contacts().size(), 0u);
}

TEST(DdaStage, BlockBelowTheFrictionAngleDoesNotCreep) {
  // theta = 20 deg <= phi = 30 deg: after settling (elastic shear deflection
  // m g sin(theta) / (4 k_s) = 0.4 um) the block does not move: creep over
  // 1e4 steps below 1e-7 m (the validation test runs 1e5).
  Incline inc(20.0, 30.0);
  inc.scene.run_steps(2000);
  const double settled = inc.travelled();
  EXPECT_LT(std::abs(settled), 2e-6);
  inc.scene.run_steps(10000);
  EXPECT_LT(std::abs(inc.travelled() - settled), 1e-7) << "creep " << inc.travelled() - settled;
}

namespace {

enum Failure { stable = 0, slides = 1, topples = 2, both = 3 };

// A block of base b (along the slope) and height h on a horizontal slab under
// gravity tilted by theta: sliding vs toppling after 0.4 s.
Failure failure_mode(double theta, double phi, double b, double h) {
  BlockScene s({g * std::sin(theta * deg), 0.0, -g * std::cos(theta * deg)});
  s.add_block(block("bed", box({-2, -1, -0.2}, {6, 1, 0}), ", \"fixed\": true"), contact(phi));
  s.add_block(block("column", box({0, -0.1, 0}, {b, 0.1, h})), contact(phi));
  s.start();
  const auto& blocks = s.blocks();
  const Vec3 toe = blocks.to_world(1, {0.5 * b, 0.0, -0.5 * h});  // downhill bottom edge
  // Hoek-Bray is a criterion for the onset of failure: sliding is judged by
  // the toe's slip until the block has tilted 10 degrees (a column far over
  // drags its toe whatever the friction).
  double tilt = 0.0, slip = 0.0;
  while (s.world.time < 0.4) {
    s.run_steps(1);
    tilt = 2.0 * std::acos(std::min(1.0, std::abs(blocks.orientation[1].w))) / deg;
    if (tilt < 10.0) slip = blocks.to_world(1, {0.5 * b, 0.0, -0.5 * h}).x - toe.x;
  }
  const bool slid = slip > 2e-4;  // elastic shear slip is ~1e-6 m; sliding moves the toe by mm
  const bool toppled = tilt > 3.0;
  std::printf("theta %g phi %g b/h %.3g: toe slip %.4g m, tilt %.3g deg\n", theta, phi, b / h, slip, tilt);
  return static_cast<Failure>((slid ? slides : 0) | (toppled ? topples : 0));
}

}  // namespace

TEST(DdaStage, SlidingVersusTopplingFollowsHoekBray) {
  // Hoek & Bray (1981): slides if tan(phi) < tan(theta), topples if b/h < tan(theta).
  struct Case {
    double theta, phi, b, h;
  };
  const Case cases[] = {
      {20, 35, 0.3, 0.3},   // stable: b/h = 1 > tan 20 = 0.36, phi > theta
      {30, 20, 0.3, 0.3},   // slides only
      {30, 45, 0.1, 0.4},   // topples only: b/h = 0.25 < tan 30 = 0.58
      {40, 20, 0.1, 0.4},   // slides and topples
      {20, 35, 0.1, 0.4},   // topples: 0.25 < 0.36
      {15, 35, 0.15, 0.4},  // stable: b/h = 0.375 > tan 15 = 0.27
  };
  for (const auto& c : cases) {
    const bool slide = std::tan(c.phi * deg) < std::tan(c.theta * deg);
    const bool topple = c.b / c.h < std::tan(c.theta * deg);
    const int expected = (slide ? slides : 0) | (topple ? topples : 0);
    EXPECT_EQ(failure_mode(c.theta, c.phi, c.b, c.h), expected)
        << "theta " << c.theta << " phi " << c.phi << " b/h " << c.b / c.h;
  }
}

// Energy scale of the drop tests: m g H, 20 kg falling 0.3 m = 58.9 J.
constexpr double drop_energy = 20 * g * 0.3;

TEST(DdaStage, BounceWithoutDampingKeepsItsEnergy) {
  BlockScene s;
  s.add_block(block("floor", box({-2, -2, -0.5}, {2, 2, 0}), ", \"fixed\": true"), contact(30, 0.0));
  s.add_block(block("rock", box({-0.1, -0.1, 0.3}, {0.1, 0.1, 0.5})), contact(30, 0.0));
  s.start();
  const auto& e = s.blocks().energy;
  const double e0 = e.kinetic + e.potential + e.strain;
  double highest_after_bounce = 0.0, worst = 0.0;
  bool touched = false;
  while (s.world.time < 0.6) {
    s.run_steps(1);
    worst = std::max(worst, std::abs(e.kinetic + e.potential + e.strain - e0));
    touched = touched || !s.stage->contacts().key.empty();
    if (touched) highest_after_bounce = std::max(highest_after_bounce, s.blocks().position[1].z);
  }
  EXPECT_TRUE(touched);
  // Bounded: a penalty contact switched on and off between steps errs by
  // about k (v dt)^2 per point; here 1.4 % of m g H.
  EXPECT_LT(worst / drop_energy, 0.03) << "energy drift " << worst << " J";
  // Elastic: back close to the drop height (centroid at 0.4 m).
  EXPECT_GT(highest_after_bounce, 0.39);
}

TEST(DdaStage, DampedBounceDissipatesAndBalances) {
  BlockScene s;
  s.add_block(block("floor", box({-2, -2, -0.5}, {2, 2, 0}), ", \"fixed\": true"), contact(30, 0.5));
  s.add_block(block("rock", box({-0.1, -0.1, 0.3}, {0.1, 0.1, 0.5})), contact(30, 0.5));
  s.start();
  const auto& e = s.blocks().energy;
  const double e0 = e.kinetic + e.potential + e.strain;
  s.run_until(1.0);
  const double mechanical = e.kinetic + e.potential + e.strain;
  EXPECT_NEAR(e0 - mechanical, drop_energy, 0.01 * drop_energy);  // all the drop energy is gone
  EXPECT_NEAR((mechanical + e.dissipated - e0) / drop_energy, 0.0, 0.03) << "balance";
  EXPECT_NEAR(s.blocks().position[1].z, 0.1, 1e-4);  // at rest on the floor
}

TEST(DdaStage, StackAtRestStaysAtRest) {
  BlockScene s;
  s.add_block(block("floor", box({-1, -1, -0.2}, {1, 1, 0}), ", \"fixed\": true"), contact(30));
  for (int k = 0; k < 3; ++k)
    s.add_block(block("b" + std::to_string(k), box({-0.1, -0.1, 0.2 * k}, {0.1, 0.1, 0.2 * (k + 1)})), contact(30));
  s.start();
  std::vector<Vec3> start(s.blocks().position);
  s.run_until(1.0);
  for (std::size_t i = 1; i < 4; ++i) {
    EXPECT_LT(norm(s.blocks().position[i] - start[i]), 2e-5) << s.blocks().name[i];
    EXPECT_LT(norm(s.blocks().velocity[i]), 1e-4) << s.blocks().name[i];
    EXPECT_NEAR(std::abs(s.blocks().orientation[i].w), 1.0, 1e-9);
  }
}

TEST(DdaStage, BondedJointHoldsUntilItsStrengthIsExceeded) {
  // A 20 kg cube hanging under a fixed ceiling by a bonded joint of 0.04 m^2:
  // tension 196 N = 4.9 kPa. Tensile strength 10 kPa holds, 2 kPa breaks.
  for (double strength : {1e4, 2e3}) {
    BlockScene s;
    const std::string joint = ", \"tensile_strength\": " + std::to_string(strength) + ", \"cohesion\": 1e4";
    s.add_block(block("ceiling", box({-1, -1, 0}, {1, 1, 0.2}), ", \"fixed\": true"),
                contact(30, 0.2, "mohr_coulomb", joint));
    s.add_block(block("hanging", box({-0.1, -0.1, -0.2}, {0.1, 0.1, 0})), contact(30));
    s.start();
    s.run_until(0.3);
    const double drop = -0.1 - s.blocks().position[1].z;
    if (strength > 4905)
      EXPECT_LT(drop, 1e-4) << "strength " << strength;
    else
      EXPECT_GT(drop, 0.5 * 0.5 * g * 0.3 * 0.3) << "strength " << strength;
  }
}

TEST(DdaStage, CohesionHoldsABlockOnASteepSlope) {
  // theta = 40 deg > phi = 20 deg; the joint (0.04 m^2) needs
  // c > m g (sin - cos tan phi) / A = 20 g 0.364 / 0.04 = 1.8 kPa.
  for (double c : {5e3, 0.0}) {
    BlockScene s;
    const std::string joint = ", \"cohesion\": " + std::to_string(c) + ", \"tensile_strength\": 1e4";
    s.add_block(block("slope", rotated_box_json({-1, -0.5, -0.2}, {3, 0.5, 0}, 40, {0, 0, 0}), ", \"fixed\": true"),
                contact(20, 0.2, "mohr_coulomb", joint));
    s.add_block(block("cube", rotated_box_json({0, -0.1, 0}, {0.2, 0.1, 0.2}, 40, {0, 0, 0})), contact(20));
    s.start();
    const Vec3 x0 = s.blocks().position[1];
    s.run_until(0.3);
    const double moved = norm(s.blocks().position[1] - x0);
    if (c > 0)
      EXPECT_LT(moved, 1e-4);
    else
      EXPECT_GT(moved, 0.05);
  }
}

TEST(DdaStage, PrescribedMotionDrivesABlockAndFrictionDragsAnother) {
  BlockScene s;
  s.add_block(block("belt", box({-2, -1, -0.2}, {2, 1, 0}), ", \"motion\": {\"velocity\": {\"velocity\": [0.5, 0, 0]}}"),
              contact(30));
  s.add_block(block("rider", box({-0.1, -0.1, 0}, {0.1, 0.1, 0.2})), contact(30));
  s.start();
  s.run_until(1.0);
  const auto& b = s.blocks();
  EXPECT_NEAR(b.position[0].x, 0.5, 1e-9);
  EXPECT_NEAR(b.velocity[0].x, 0.5, 1e-12);
  // The rider accelerates at g tan(30) = 5.7 m/s^2 until it moves with the belt.
  EXPECT_NEAR(b.velocity[1].x, 0.5, 1e-3);
}

TEST(DdaStage, SubcyclingSplitsACoarseHostStep) {
  BlockScene s;
  s.add_block(block("floor", box({-2, -2, -0.5}, {2, 2, 0}), ", \"fixed\": true"), contact(30));
  s.add_block(block("rock", box({-0.1, -0.1, 0}, {0.1, 0.1, 0.2})), contact(30));
  auto& stage = s.start(R"({"subcycle": true})");
  EXPECT_TRUE(std::isinf(stage.stable_time_step(s.world)));
  const double own = stage.own_time_step();
  s.run_steps(100, 10.0 * own);
  EXPECT_GE(stage.last_substeps(), 10);
  EXPECT_LE(stage.last_substeps(), 12);
  EXPECT_NEAR(s.blocks().position[1].z, 0.1, 1e-5);  // still resting
}

TEST(DdaStage, ExternalForcesAreAppliedOnceAndCleared) {
  BlockScene s({0, 0, 0});
  s.add_block(block("rock", box({0, 0, 0}, {1, 1, 1})), contact(30));
  auto& stage = s.start();
  const double h = stage.own_time_step();
  s.run_steps(1, h);                              // past the leapfrog's half-kick start
  s.blocks().external_force[0] = {2500.0, 0, 0};  // 1 m/s^2, held over one host step of 10 sub-steps
  s.run_steps(1, 10 * h);
  EXPECT_EQ(s.blocks().external_force[0].x, 0.0);
  EXPECT_EQ(stage.last_substeps(), 10);
  s.run_steps(50, h);
  const double v = 10 * h;
  EXPECT_NEAR(s.blocks().velocity[0].x, v, 1e-12);
  EXPECT_NEAR(s.blocks().energy.external_work / (0.5 * 2500 * v * v), 1.0, 1e-9);
  EXPECT_NEAR(s.blocks().energy.kinetic / (0.5 * 2500 * v * v), 1.0, 1e-9);
}

TEST(DdaStage, SetupErrorsNameTheBlock) {
  BlockScene s;
  s.add_block(block("rock", box({0, 0, 0}, {1, 1, 1})), contact(30));
  s.world.bodies[0].contact = nullptr;
  try {
    s.start();
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("block 'rock' needs a contact model"), std::string::npos) << e.what();
  }
  BlockScene flat;
  flat.world.dim = 2;
  flat.add_block(block("rock", box({0, 0, 0}, {1, 1, 1})), contact(30));
  EXPECT_THROW(flat.start(), InputError);
}

TEST(DdaStage, LocalDampingBringsABlockToRestWithItsEnergyBalanced) {
  // Contact damping off: only the local (non-viscous) damping takes the drop energy out.
  BlockScene s;
  s.add_block(block("floor", box({-2, -2, -0.5}, {2, 2, 0}), ", \"fixed\": true"), contact(30, 0.0));
  s.add_block(block("rock", box({-0.1, -0.1, 0.3}, {0.1, 0.1, 0.5})), contact(30, 0.0));
  DdaStage& stage = s.start();
  stage.set_local_damping(0.8);
  const auto& e = s.blocks().energy;
  const double e0 = e.kinetic + e.potential + e.strain;
  s.run_until(1.0);
  const double mechanical = e.kinetic + e.potential + e.strain;
  EXPECT_NEAR(e0 - mechanical, drop_energy, 0.01 * drop_energy);
  EXPECT_NEAR((mechanical + e.dissipated - e0) / drop_energy, 0.0, 0.03) << "balance";
  EXPECT_LT(stage.unbalanced_ratio(), 1e-6);  // static equilibrium: the springs carry the weight
  EXPECT_NEAR(s.blocks().position[1].z, 0.1, 1e-4);
}
