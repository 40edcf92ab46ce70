// Equations of state against hand values: pressure, sound speed and the
// inverse density_at for Tait, linear and ideal gas.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "ideal_gas.hpp"
#include "talus/error.hpp"
#include "linear.hpp"
#include "tait.hpp"

namespace {

using talus::Index;

struct Batch {
  std::vector<double> rho, p, c;
  std::vector<Index> idx;
  explicit Batch(std::vector<double> r) : rho(std::move(r)), p(rho.size(), -1.0), c(rho.size(), -1.0) {
    for (std::size_t i = 0; i < rho.size(); ++i) idx.push_back(static_cast<Index>(i));
  }
  void run(const talus::EquationOfState& eos) { eos.pressure(idx, rho.data(), p.data(), c.data()); }
};

TEST(Tait, HandValues) {
  talus::eos::Tait eos(talus::params_from_json(talus::eos::Tait::describe(), R"({"c0": 20})"));
  eos.set_reference_density(1000.0);
  // B = rho0 c0^2 / gamma = 1000 * 400 / 7 = 57142.857...
  EXPECT_NEAR(eos.stiffness(), 400000.0 / 7.0, 1e-9);
  Batch b({1000.0, 1010.0, 990.0});
  b.run(eos);
  EXPECT_NEAR(b.p[0], 0.0, 1e-9);
  EXPECT_NEAR(b.p[1], 400000.0 / 7.0 * (std::pow(1.01, 7) - 1.0), 1e-7);  // 1.01^7 = 1.0721353521
  EXPECT_NEAR(b.p[1], 4122.0201, 1e-3);
  EXPECT_NEAR(b.p[2], 400000.0 / 7.0 * (std::pow(0.99, 7) - 1.0), 1e-7);
  EXPECT_NEAR(b.c[0], 20.0, 1e-12);
  EXPECT_NEAR(b.c[1], 20.0 * std::pow(1.01, 3), 1e-12);  // c = c0 (rho/rho0)^((gamma-1)/2)
  EXPECT_EQ(eos.reference_sound_speed(), 20.0);
  for (double p : {0.0, 500.0, 9810.0, -1000.0}) {
    const double rho = eos.density_at(p);
    Batch one({rho});
    one.run(eos);
    EXPECT_NEAR(one.p[0], p, 1e-8 * (1.0 + std::abs(p)));
  }
}

TEST(Tait, GeneralGammaUsesPow) {
  talus::eos::Tait eos(talus::params_from_json(talus::eos::Tait::describe(), R"({"c0": 30, "gamma": 1.4})"));
  eos.set_reference_density(1.2);
  Batch b({1.5});
  b.run(eos);
  const double B = 1.2 * 900.0 / 1.4;
  EXPECT_NEAR(b.p[0], B * (std::pow(1.25, 1.4) - 1.0), 1e-9);
  EXPECT_NEAR(b.c[0], 30.0 * std::pow(1.25, 0.2), 1e-12);
  // c^2 = dp/drho
  const double e = 1e-6;
  Batch pm({1.5 + e, 1.5 - e});
  pm.run(eos);
  EXPECT_NEAR((pm.p[0] - pm.p[1]) / (2 * e), b.c[0] * b.c[0], 1e-4);
}

TEST(Linear, HandValues) {
  talus::eos::Linear eos(talus::params_from_json(talus::eos::Linear::describe(), R"({"k": 400})"));
  eos.set_reference_density(1000.0);
  Batch b({1000.0, 1002.5, 999.0});
  b.run(eos);
  EXPECT_DOUBLE_EQ(b.p[0], 0.0);
  EXPECT_DOUBLE_EQ(b.p[1], 1000.0);
  EXPECT_DOUBLE_EQ(b.p[2], -400.0);
  EXPECT_DOUBLE_EQ(b.c[1], 20.0);
  EXPECT_DOUBLE_EQ(eos.density_at(1000.0), 1002.5);
  EXPECT_DOUBLE_EQ(eos.reference_sound_speed(), 20.0);
}

TEST(IdealGas, HandValues) {
  talus::eos::IdealGas eos(talus::params_from_json(talus::eos::IdealGas::describe(), R"({"k": 100})"));
  eos.set_reference_density(1000.0);
  Batch b({1000.0, 2.0});
  b.run(eos);
  EXPECT_DOUBLE_EQ(b.p[0], 100000.0);
  EXPECT_DOUBLE_EQ(b.p[1], 200.0);
  EXPECT_DOUBLE_EQ(b.c[0], 10.0);
  EXPECT_DOUBLE_EQ(eos.density_at(200.0), 2.0);
}

// Only the listed indices are written.
TEST(Tait, WritesOnlyTheGivenIndices) {
  talus::eos::Tait eos(talus::params_from_json(talus::eos::Tait::describe(), R"({"c0": 10})"));
  eos.set_reference_density(1000.0);
  std::vector<double> rho{1001.0, 1002.0, 1003.0}, p(3, -7.0), c(3, -7.0);
  const std::vector<Index> idx{2};
  eos.pressure(idx, rho.data(), p.data(), c.data());
  EXPECT_EQ(p[0], -7.0);
  EXPECT_EQ(p[1], -7.0);
  EXPECT_GT(p[2], 0.0);
}

TEST(Eos, RejectsBadParameters) {
  EXPECT_THROW(talus::params_from_json(talus::eos::Tait::describe(), R"({"c0": -1})"), talus::InputError);
  EXPECT_THROW(talus::params_from_json(talus::eos::Tait::describe(), R"({"gamma": 7})"), talus::InputError);
  EXPECT_THROW(talus::params_from_json(talus::eos::Linear::describe(), R"({"k": 0})"), talus::InputError);
}

}  // namespace
