#include <gtest/gtest.h>

#include <cmath>

#include "carreau.hpp"
#include "talus/error.hpp"

namespace {

example::Carreau make(const char* json) { return example::Carreau(talus::params_from_json(example::Carreau::describe(), json)); }

TEST(Carreau, HandValues) {
  const auto c = make(R"({"zero_shear_viscosity": 10, "infinite_shear_viscosity": 0.1,
                          "time_constant": 2, "flow_index": 0.5})");
  EXPECT_DOUBLE_EQ(c.viscosity(0.0), 10.0);
  // lambda gamma = 1: 0.1 + 9.9 * 2^(-1/4)
  EXPECT_NEAR(c.viscosity(0.5), 0.1 + 9.9 * std::pow(2.0, -0.25), 1e-12);
  // High shear: approaches mu_inf.
  EXPECT_NEAR(c.viscosity(1e9), 0.1, 1e-3);
}

TEST(Carreau, BatchCallFillsOnlyTheGivenParticles) {
  const auto c = make(R"({"zero_shear_viscosity": 1, "time_constant": 1, "flow_index": 0.5})");
  const double rate[3] = {0.0, 1.0, 3.0};
  double mu[3] = {-1, -1, -1};
  const talus::Index idx[2] = {0, 2};
  c.apparent_viscosity(idx, talus::ViscosityInputs{rate, nullptr, nullptr}, mu);
  EXPECT_DOUBLE_EQ(mu[0], 1.0);
  EXPECT_DOUBLE_EQ(mu[1], -1.0);
  EXPECT_NEAR(mu[2], std::pow(10.0, -0.25), 1e-12);
}

TEST(Carreau, DeclarationRejectsThickening) {
  EXPECT_THROW(make(R"({"zero_shear_viscosity": 1, "infinite_shear_viscosity": 2, "time_constant": 1,
                        "flow_index": 0.5})"), talus::InputError);
}

}  // namespace
