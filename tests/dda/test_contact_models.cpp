// Contact models against hand values of the joint law (joint_law.hpp):
// normal spring, damping, stick and slip, tensile and shear failure of bonds.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "mohr_coulomb.hpp"
#include "penalty_coulomb.hpp"

using namespace talus;
using namespace talus::dda;

namespace {

// One contact with normal +z between a (below) and b (above).
struct One {
  double gap = 0.0, area = 0.0, mass = 1.0;
  Vec3 normal{0, 0, 1}, velocity{}, shear{}, force{};
  std::uint8_t state = contact_open;
  double strain = 0.0, dissipated = 0.0;
  ContactBatch batch() {
    ContactBatch b;
    b.size = 1;
    b.gap = &gap;
    b.normal = &normal;
    b.velocity = &velocity;
    b.area = &area;
    b.mass = &mass;
    b.shear = &shear;
    b.state = &state;
    b.force = &force;
    b.strain_energy = &strain;
    b.dissipated = &dissipated;
    return b;
  }
};

contact::PenaltyCoulomb penalty(const char* json) {
  return contact::PenaltyCoulomb(params_from_json(contact::PenaltyCoulomb::describe(), json));
}

}  // namespace

TEST(DdaContactModels, NormalSpringAndDamping) {
  auto m = penalty(R"({"normal_stiffness": 1e6, "friction_angle": 30, "damping_ratio": 0})");
  One c;
  c.gap = -1e-3;
  m.compute(c.batch(), 1e-3);
  EXPECT_NEAR(c.force.z, 1000.0, 1e-9);
  EXPECT_NEAR(c.strain, 0.5 * 1e6 * 1e-6, 1e-12);
  EXPECT_EQ(c.state & contact_state_mask, contact_stick);
  EXPECT_EQ(m.max_stiffness(), 1e6);
  // Damping ratio 0.5, m = 1 kg: c_n = 2 xi sqrt(k m) = 1000 N s/m; approaching at 1 m/s.
  auto d = penalty(R"({"normal_stiffness": 1e6, "friction_angle": 30, "damping_ratio": 0.5})");
  One e;
  e.gap = -1e-3;
  e.velocity = {0, 0, -1};
  d.compute(e.batch(), 1e-4);
  EXPECT_NEAR(e.force.z, 1000.0 + 1000.0, 1e-9);
  // Dissipated: c v v_mid dt, v_mid = v + F dt / 2m.
  EXPECT_NEAR(e.dissipated, 1000.0 * 1.0 * (1.0 - 2000.0 * 1e-4 / 2.0) * 1e-4, 1e-12);
  // Separating fast: the damping cannot pull, the force is clamped to zero.
  One f;
  f.gap = -1e-3;
  f.velocity = {0, 0, 5};
  d.compute(f.batch(), 1e-4);
  EXPECT_EQ(f.force.z, 0.0);
}

TEST(DdaContactModels, OpenContactResetsItsHistory) {
  auto m = penalty(R"({"normal_stiffness": 1e6, "friction_angle": 30, "damping_ratio": 0})");
  One c;
  c.gap = 1e-4;
  c.shear = {1e-3, 0, 0};
  c.state = contact_stick;
  m.compute(c.batch(), 1e-3);
  EXPECT_EQ(c.force.x, 0.0);
  EXPECT_EQ(c.force.z, 0.0);
  EXPECT_EQ(c.shear.x, 0.0);
  EXPECT_EQ(c.state, contact_open);
}

TEST(DdaContactModels, StickThenSlipAtTheCoulombLimit) {
  // k_s defaults to 0.4 k_n = 4e5 N/m; F_n = 1000 N, tan 30 = 0.577: limit 577.35 N.
  auto m = penalty(R"({"normal_stiffness": 1e6, "friction_angle": 30, "damping_ratio": 0})");
  EXPECT_NEAR(m.parameters().shear_stiffness, 4e5, 1e-9);
  One c;
  c.gap = -1e-3;
  c.velocity = {0.1, 0, 0};
  m.compute(c.batch(), 1e-3);  // u_s = 1e-4 m: 40 N, sticks
  EXPECT_NEAR(c.shear.x, 1e-4, 1e-15);
  EXPECT_NEAR(c.force.x, -40.0, 1e-9);
  EXPECT_EQ(c.state & contact_state_mask, contact_stick);
  const double limit = 1000.0 * std::tan(30.0 * M_PI / 180.0);
  for (int k = 0; k < 20; ++k) m.compute(c.batch(), 1e-3);  // 2.1 mm: beyond the limit
  EXPECT_EQ(c.state & contact_state_mask, contact_slip);
  EXPECT_NEAR(c.force.x, -limit, 1e-9);
  EXPECT_NEAR(c.shear.x, limit / 4e5, 1e-15);
  EXPECT_NEAR(c.dissipated, limit * 1e-4, 1e-9);  // sliding 0.1 mm per step at the limit
  // The spring is carried into a tilted tangent plane without changing length.
  c.normal = {0, std::sin(0.1), std::cos(0.1)};
  c.velocity = {};
  const double before = norm(c.shear);
  m.compute(c.batch(), 1e-3);
  EXPECT_NEAR(dot(c.shear, c.normal), 0.0, 1e-18);
  EXPECT_NEAR(norm(c.shear), before, 1e-15);
}

TEST(DdaContactModels, MohrCoulombBondsBreakInTensionAndShear) {
  const auto p = params_from_json(contact::MohrCoulomb::describe(),
                                  R"({"normal_stiffness": 1e6, "friction_angle": 30, "damping_ratio": 0,
                                      "cohesion": 1e4, "tensile_strength": 2e4})");
  contact::MohrCoulomb m(p);
  EXPECT_EQ(m.initial_state(), contact_bonded);
  // Area 0.01 m^2: tensile capacity 200 N, cohesion 100 N.
  One c;
  c.area = 0.01;
  c.state = contact_bonded;
  c.gap = 1e-4;  // 100 N of tension: holds
  m.compute(c.batch(), 1e-3);
  EXPECT_NEAR(c.force.z, -100.0, 1e-9);
  EXPECT_TRUE(c.state & contact_bonded);
  c.gap = 3e-4;  // 300 N: breaks, and the contact is open
  m.compute(c.batch(), 1e-3);
  EXPECT_FALSE(c.state & contact_bonded);
  EXPECT_EQ(c.force.z, 0.0);
  c.gap = 1e-4;  // never bonds again
  m.compute(c.batch(), 1e-3);
  EXPECT_EQ(c.force.z, 0.0);

  // Shear: F_n = 1000 N, capacity 100 + 577 N; 600 N holds, 700 N breaks to friction only.
  One s;
  s.area = 0.01;
  s.state = contact_bonded;
  s.gap = -1e-3;
  s.shear = {600.0 / 4e5, 0, 0};
  m.compute(s.batch(), 1e-3);
  EXPECT_TRUE(s.state & contact_bonded);
  EXPECT_NEAR(s.force.x, -600.0, 1e-9);
  s.shear = {700.0 / 4e5, 0, 0};
  m.compute(s.batch(), 1e-3);
  EXPECT_FALSE(s.state & contact_bonded);
  EXPECT_EQ(s.state & contact_state_mask, contact_slip);
  EXPECT_NEAR(s.force.x, -1000.0 * std::tan(30.0 * M_PI / 180.0), 1e-9);
}

TEST(DdaContactModels, PerfectlyPlasticJointsKeepTheirCohesionWhileSlipping) {
  const auto p = params_from_json(contact::MohrCoulomb::describe(),
                                  R"({"normal_stiffness": 1e6, "friction_angle": 30, "damping_ratio": 0,
                                      "cohesion": 1e4, "shear_softening": "none"})");
  contact::MohrCoulomb m(p);
  // F_n = 1000 N, capacity c A + F_n tan(phi) = 100 + 577 N: 700 N slips at the full capacity, still bonded.
  One s;
  s.area = 0.01;
  s.state = contact_bonded;
  s.gap = -1e-3;
  s.shear = {700.0 / 4e5, 0, 0};
  const double capacity = 100.0 + 1000.0 * std::tan(30.0 * M_PI / 180.0);
  for (int step = 0; step < 3; ++step) {
    m.compute(s.batch(), 1e-3);
    EXPECT_TRUE(s.state & contact_bonded);
    EXPECT_EQ(s.state & contact_state_mask, contact_slip);
    EXPECT_NEAR(s.force.x, -capacity, 1e-9);
    s.shear.x *= 1.2;  // keeps being dragged
  }
  // A tensile failure still breaks the bond (no tensile strength here: any tension).
  s.gap = 1e-5;
  m.compute(s.batch(), 1e-3);
  EXPECT_FALSE(s.state & contact_bonded);
}
