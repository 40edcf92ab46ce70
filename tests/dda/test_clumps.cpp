// Clumps: blocks that share a "clump" name move as one rigid body. A cube cut
// in two and clumped slides down an incline as the whole cube does; a
// clump spins free of torque keeping its energy, angular momentum and shape;
// its pieces may overlap without forces; bad clumps are refused by name.
// Also: a bond joins only faces that touch at the start, and mass scaling
// changes the step but not the equilibrium.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
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

// Distance travelled down a 30-degree incline (joint friction 20 degrees) in
// 1 s by a 0.2 m cube, whole or cut in `pieces` slices across the slope
// that form one clump.
double travelled_down_incline(int pieces) {
  const double theta = 30.0;
  BlockScene s;
  s.add_block(block("slope", rotated_box_json({-1, -0.5, -0.2}, {3, 0.5, 0}, theta, {0, 0, 0}), ", \"fixed\": true"),
              contact(20));
  for (int k = 0; k < pieces; ++k) {
    const double y0 = -0.1 + 0.2 * k / pieces, y1 = -0.1 + 0.2 * (k + 1) / pieces;
    s.add_block(block("piece" + std::to_string(k), rotated_box_json({0, y0, 0}, {0.2, y1, 0.2}, theta, {0, 0, 0}),
                      pieces > 1 ? ", \"clump\": \"cube\"" : ""),
                contact(20));
  }
  s.start();
  const Vec3 down{std::cos(theta * deg), 0.0, -std::sin(theta * deg)};
  const Vec3 start = s.blocks().position[1];
  const Vec3 apart = s.blocks().position[pieces] - s.blocks().position[1];
  s.run_until(1.0);
  // The pieces keep their places in the clump and its orientation.
  EXPECT_LT(norm(s.blocks().position[pieces] - s.blocks().position[1] - apart), 1e-12);
  for (int k = 1; k <= pieces; ++k) EXPECT_NEAR(std::abs(s.blocks().orientation[k].w), 1.0, 1e-6);
  return dot(s.blocks().position[1] - start, down);
}

const char* b_name(std::size_t i) { return i == 1 ? "cube" : (i == 2 ? "pebble" : "stone"); }

}  // namespace

TEST(Clumps, ACubeCutInPiecesSlidesAsTheWholeCube) {
  const double a = g * (std::sin(30 * deg) - std::cos(30 * deg) * std::tan(20 * deg));
  const double whole = travelled_down_incline(1);
  for (int pieces : {2, 4}) {
    const double cut = travelled_down_incline(pieces);
    std::printf("incline 30/20, %d pieces: travelled %.6f m, whole cube %.6f m, analytic %.6f m\n", pieces, cut,
                whole, 0.5 * a);
    EXPECT_NEAR(cut / (0.5 * a), 1.0, 0.01);
    EXPECT_NEAR(cut / whole, 1.0, 2e-3);
  }
}

TEST(Clumps, AClumpSpinsFreeOfTorqueAsOneRigidBody) {
  // An L of three cubes, no gravity, spinning about an axis that is not a
  // principal one: energy and angular momentum are kept, and so are the
  // distances between the pieces.
  BlockScene s({0.0, 0.0, 0.0});
  const char* spin = ", \"clump\": \"L\", \"angular_velocity\": [1.0, 2.0, 3.0]";
  s.add_block(block("a", box({0, 0, 0}, {0.2, 0.2, 0.2}), spin), contact(30));
  s.add_block(block("b", box({0.2, 0, 0}, {0.4, 0.2, 0.2}), spin), contact(30));
  s.add_block(block("c", box({0, 0.2, 0}, {0.2, 0.4, 0.2}), spin), contact(30));
  s.start();
  auto& b = s.blocks();
  const Vec3 ab = b.position[1] - b.position[0], ac = b.position[2] - b.position[0];
  // Angular momentum about the clump's centroid: each piece's own plus its orbit.
  auto momentum = [&]() {
    Vec3 centre{}, l{};
    double mass = 0.0;
    for (std::size_t i = 0; i < 3; ++i) {
      centre += b.mass[i] * b.position[i];
      mass += b.mass[i];
    }
    centre = centre / mass;
    for (std::size_t i = 0; i < 3; ++i) {
      const Vec3 r = b.position[i] - centre;
      const double s2 = 0.2 * 0.2;
      const Vec3 own = (b.mass[i] * s2 / 6.0) * b.angular_velocity[i];  // a cube's inertia is isotropic
      l += own + b.mass[i] * cross(r, b.velocity[i]);
    }
    return l;
  };
  const Vec3 l0 = momentum();
  const double e0 = b.energy.kinetic;
  s.run_until(2.0);
  EXPECT_NEAR(norm(b.position[1] - b.position[0]), norm(ab), 1e-12);
  EXPECT_NEAR(norm(b.position[2] - b.position[0]), norm(ac), 1e-12);
  EXPECT_NEAR(norm(b.position[2] - b.position[1]), norm(ac - ab), 1e-12);
  EXPECT_LT(norm(momentum() - l0) / norm(l0), 1e-3);
  EXPECT_NEAR(b.energy.kinetic / e0, 1.0, 1e-3);
  EXPECT_EQ(s.stage->contacts().size(), 0u);  // three touching cubes, one body
}

TEST(Clumps, OverlappingPiecesFallFreelyWithoutForcesBetweenThem) {
  BlockScene s;
  s.add_block(block("a", box({0, 0, 0}, {0.3, 0.2, 0.2}), ", \"clump\": \"x\""), contact(30));
  s.add_block(block("b", box({0.1, 0.05, 0.05}, {0.4, 0.25, 0.25}), ", \"clump\": \"x\""), contact(30));
  s.start();
  const double z0 = s.blocks().position[0].z;
  s.run_until(0.5);
  EXPECT_NEAR(z0 - s.blocks().position[0].z, 0.5 * g * 0.25, 1e-9);
  EXPECT_LT(norm(s.blocks().angular_velocity[0]), 1e-12);
}

TEST(Clumps, FixedOrDivergingPiecesAreRefusedByName) {
  auto message = [](const std::string& extra_a, const std::string& extra_b) {
    BlockScene s;
    s.add_block(block("a", box({0, 0, 0}, {1, 1, 1}), ", \"clump\": \"pair\"" + extra_a), contact(30));
    s.add_block(block("b", box({1, 0, 0}, {2, 1, 1}), ", \"clump\": \"pair\"" + extra_b), contact(30));
    try {
      s.start();
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  // (The test world gives each body the file's root as its path; the host's is /bodies/N.)
  std::string m = message(", \"fixed\": true", "");
  EXPECT_NE(m.find("/clump: block 'a' is fixed"), std::string::npos) << m;
  m = message("", ", \"velocity\": [1, 0, 0]");
  EXPECT_NE(m.find("/clump: block 'b'"), std::string::npos) << m;
  EXPECT_NE(m.find("another velocity than block 'a'"), std::string::npos) << m;
}

TEST(Bonds, FacesApartAtTheStartAreNotBonded) {
  // A 20 kg cube 1 mm under a fixed ceiling, inside the contact margin
  // (1 % of the smallest radius, 1.7 mm), with a joint far stronger than the
  // springs' pull across that gap (k_n 1 mm = 1e5 N a point): with no face
  // contact there is no bond, and the cube falls. Touching, it hangs.
  for (double gap : {1e-3, 0.0}) {
    BlockScene s;
    const std::string joint = ", \"tensile_strength\": 1e9, \"cohesion\": 1e9";
    s.add_block(block("ceiling", box({-1, -1, 0}, {1, 1, 0.2}), ", \"fixed\": true"),
                contact(30, 0.2, "mohr_coulomb", joint));
    s.add_block(block("cube", box({-0.1, -0.1, -0.2 - gap}, {0.1, 0.1, -gap})), contact(30));
    s.start();
    ASSERT_EQ(s.stage->contacts().size(), 4u) << "gap " << gap;  // tracked either way
    const double z0 = s.blocks().position[1].z;
    s.run_until(0.2);
    const double drop = z0 - s.blocks().position[1].z;
    if (gap > 0.0)
      EXPECT_NEAR(drop, 0.5 * g * 0.2 * 0.2, 1e-6) << "an open joint must not pull";
    else
      EXPECT_LT(drop, 1e-5);
  }
}

TEST(MassScaling, ALongerStepAndTheSameEquilibrium) {
  // A 0.4 m cube with a 2 cm pebble on it and another on the floor: the
  // pebbles set the step. Scaled, each body takes the cube's frequency.
  auto settle = [](bool scaled, double& step) {
    BlockScene s;
    s.add_block(block("floor", box({-1, -1, -0.2}, {1, 1, 0}), ", \"fixed\": true"), contact(30, 0.0));
    s.add_block(block("cube", box({-0.2, -0.2, 0}, {0.2, 0.2, 0.4})), contact(30, 0.0));
    s.add_block(block("pebble", box({0, 0, 0.4}, {0.02, 0.02, 0.42})), contact(30, 0.0));
    s.add_block(block("stone", box({0.5, 0.5, 0}, {0.52, 0.52, 0.02})), contact(30, 0.0));
    s.start();
    s.stage->set_local_damping(0.8);
    s.stage->set_mass_scaling(scaled);
    s.run_steps(1);
    step = s.stage->own_time_step();
    for (int k = 0; k < 200000 && !(k > 10 && s.stage->unbalanced_ratio() < 1e-9); ++k) s.run_steps(1);
    EXPECT_LT(s.stage->unbalanced_ratio(), 1e-9) << (scaled ? "scaled" : "true masses");
    return std::vector<Vec3>(s.blocks().position);
  };
  double step_true = 0.0, step_scaled = 0.0;
  const auto at_rest = settle(false, step_true);
  const auto scaled = settle(true, step_scaled);
  std::printf("stable step: true masses %.3g s, scaled %.3g s\n", step_true, step_scaled);
  EXPECT_GT(step_scaled, 5.0 * step_true);
  // The heights are the springs' equilibrium; along the joints a frictional
  // equilibrium is not unique (the pebble stops where its shear springs hold
  // it, which depends on the path), so there only nearly the same place.
  for (std::size_t i = 1; i < at_rest.size(); ++i) {
    const Vec3 d = scaled[i] - at_rest[i];
    EXPECT_LT(std::abs(d.z), 1e-12) << b_name(i);
    EXPECT_LT(std::hypot(d.x, d.y), 1e-7) << b_name(i);
  }
}
