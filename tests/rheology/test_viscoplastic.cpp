// HBP, power-law and Herschel-Bulkley apparent viscosities: hand values and
// the limits in which they must coincide (coastline seed §2.3.2).
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <vector>

#include "bingham.hpp"
#include "hbp.hpp"
#include "newtonian.hpp"
#include "power_law.hpp"

namespace {

using talus::Index;

template <class M>
M make(const char* json) {
  return M(talus::params_from_json(M::describe(), json));
}

// mu_eff at the given shear rates and pressures.
template <class M>
std::vector<double> mu_of(const M& model, const std::vector<double>& gd, const std::vector<double>& p = {}) {
  const std::size_t n = gd.size();
  std::vector<Index> idx(n);
  std::iota(idx.begin(), idx.end(), Index{0});
  std::vector<double> pressure = p.empty() ? std::vector<double>(n, 0.0) : p, rho(n, 1000.0), mu(n, -1.0);
  model.apparent_viscosity(idx, talus::ViscosityInputs{gd.data(), pressure.data(), rho.data()}, mu.data());
  return mu;
}

const std::vector<double> rates{1e-3, 0.01, 0.1, 1.0, 4.0, 10.0, 100.0};

TEST(Hbp, HandValue) {
  // tau_y (1 - e^{-m gd})/gd + K gd^(n-1): tau_y = 10, m = 0.5, K = 2, n = 0.5, gd = 4
  const auto hbp = make<talus::rheology::Hbp>(
      R"({"yield_stress": 10, "regularisation": 0.5, "consistency": 2, "power_index": 0.5})");
  const double expected = 10.0 * (1.0 - std::exp(-2.0)) / 4.0 + 2.0 / std::sqrt(4.0);  // 2.1617 + 1
  EXPECT_NEAR(mu_of(hbp, {4.0})[0], expected, 1e-12);
  EXPECT_NEAR(expected, 3.1616618, 1e-6);
}

TEST(Hbp, NewtonianLimit) {
  const auto hbp = make<talus::rheology::Hbp>(R"({"yield_stress": 10, "regularisation": 0, "consistency": 0.126})");
  for (double mu : mu_of(hbp, rates)) EXPECT_DOUBLE_EQ(mu, 0.126);
}

TEST(Hbp, EqualsBinghamForNEqualsOne) {
  const auto hbp = make<talus::rheology::Hbp>(R"({"yield_stress": 3, "regularisation": 100, "consistency": 0.2})");
  const auto bingham = make<talus::rheology::Bingham>(R"({"yield_stress": 3, "regularisation": 100, "viscosity": 0.2})");
  const auto a = mu_of(hbp, rates), b = mu_of(bingham, rates);
  for (std::size_t k = 0; k < rates.size(); ++k) EXPECT_NEAR(a[k], b[k], 1e-12 * b[k]) << rates[k];
}

TEST(Hbp, LargeMReproducesUnregularisedBingham) {
  // m -> inf: mu = mu_p + tau_y / gd wherever m gd >> 1.
  const auto hbp = make<talus::rheology::Hbp>(R"({"yield_stress": 3, "regularisation": 1e6, "consistency": 0.2})");
  const auto a = mu_of(hbp, rates);
  for (std::size_t k = 0; k < rates.size(); ++k) EXPECT_NEAR(a[k], 0.2 + 3.0 / rates[k], 1e-9 * a[k]) << rates[k];
  // and at rest it stays bounded: mu_p + tau_y m
  EXPECT_NEAR(mu_of(hbp, {0.0})[0], 0.2 + 3e6, 1e-6);
}

TEST(Hbp, EqualsPowerLawWithoutYieldStress) {
  const auto hbp = make<talus::rheology::Hbp>(R"({"yield_stress": 0, "consistency": 1.5, "power_index": 0.6})");
  const auto pl = make<talus::rheology::PowerLaw>(R"({"consistency": 1.5, "power_index": 0.6})");
  const auto a = mu_of(hbp, rates), b = mu_of(pl, rates);
  for (std::size_t k = 0; k < rates.size(); ++k) {
    EXPECT_NEAR(a[k], b[k], 1e-12 * b[k]);
    EXPECT_NEAR(b[k], 1.5 * std::pow(rates[k], -0.4), 1e-12 * b[k]);
  }
}

TEST(Hbp, LargeMEqualsHerschelBulkley) {
  const auto hbp = make<talus::rheology::Hbp>(
      R"({"yield_stress": 10, "regularisation": 1e6, "consistency": 2, "power_index": 0.5})");
  const auto hb = make<talus::rheology::HerschelBulkley>(
      R"({"yield_stress": 10, "consistency": 2, "power_index": 0.5, "max_viscosity": 1e9})");
  const auto a = mu_of(hbp, rates), b = mu_of(hb, rates);
  for (std::size_t k = 0; k < rates.size(); ++k) EXPECT_NEAR(a[k], b[k], 1e-9 * b[k]) << rates[k];
  EXPECT_NEAR(b[4], 10.0 / 4.0 + 2.0 / 2.0, 1e-12);  // gd = 4 by hand: 3.5
}

TEST(HerschelBulkley, PlugViscosityIsCapped) {
  const auto hb = make<talus::rheology::HerschelBulkley>(
      R"({"yield_stress": 10, "consistency": 2, "power_index": 1, "max_viscosity": 50})");
  EXPECT_DOUBLE_EQ(mu_of(hb, {1e-3})[0], 50.0);
  EXPECT_DOUBLE_EQ(mu_of(hb, {1.0})[0], 12.0);
}

TEST(Hbp, MohrCoulombYieldStress) {
  // Table 3 sediment: c = 1 Pa, phi = 35 deg; tau_y = c + p tan(phi), p < 0 gives c.
  const auto hbp = make<talus::rheology::Hbp>(
      R"({"yield": "mohr_coulomb", "cohesion": 1, "friction_angle": 35, "regularisation": 1e6, "consistency": 0.126})");
  const auto mu = mu_of(hbp, {2.0, 2.0}, {100.0, -50.0});
  EXPECT_NEAR(mu[0], 0.126 + (1.0 + 100.0 * 0.70020753820970977) / 2.0, 1e-9);
  EXPECT_NEAR(mu[1], 0.126 + 1.0 / 2.0, 1e-9);
}

TEST(Hbp, DruckerPragerYieldStress) {
  // sqrt(J2) of the plane-strain matched cone: 3 (c + p tan phi) / sqrt(9 + 12 tan^2 phi), phi = 35 deg, c = 1 Pa,
  // p = 100 Pa. Its friction coefficient 0.545 = tan(28.6 deg): the critical slope, below phi as for any inscribed cone.
  const auto hbp = make<talus::rheology::Hbp>(
      R"({"yield": "drucker_prager", "cohesion": 1, "friction_angle": 35, "regularisation": 1e6, "consistency": 0.126})");
  const double t = 0.70020753820970977, s = std::sqrt(9.0 + 12.0 * t * t);
  const double tau_y = 3.0 * (1.0 + 100.0 * t) / s;  // 55.23 Pa
  EXPECT_NEAR(tau_y, 55.2273, 1e-3);
  EXPECT_NEAR(mu_of(hbp, {2.0}, {100.0})[0], 0.126 + tau_y / 2.0, 1e-9);
}

TEST(Hbp, MaxViscosityCapsThePlugOnly) {
  // Plug tau_y m + K = 10 * 100 + 2 = 1002 Pa s, capped at 50; a yielded rate (gd = 4/s) is below the cap: unchanged.
  const auto capped = make<talus::rheology::Hbp>(
      R"({"yield_stress": 10, "regularisation": 100, "consistency": 2, "max_viscosity": 50})");
  const auto free = make<talus::rheology::Hbp>(R"({"yield_stress": 10, "regularisation": 100, "consistency": 2})");
  EXPECT_DOUBLE_EQ(mu_of(capped, {0.0})[0], 50.0);
  EXPECT_DOUBLE_EQ(mu_of(free, {0.0})[0], 1002.0);
  EXPECT_DOUBLE_EQ(mu_of(capped, {4.0})[0], mu_of(free, {4.0})[0]);
  const auto bingham = make<talus::rheology::Bingham>(
      R"({"yield_stress": 10, "viscosity": 2, "regularisation": 100, "max_viscosity": 50})");
  EXPECT_DOUBLE_EQ(mu_of(bingham, {0.0})[0], 50.0);
  EXPECT_DOUBLE_EQ(mu_of(bingham, {4.0})[0], mu_of(free, {4.0})[0]);
}

TEST(Hbp, EffectivePressureIsTheBuoyantShare) {
  // yield_pressure effective: p' = p (1 - rho_w / rho); rho = 1000 in mu_of, rho_w = 400: p' = 0.6 p.
  const auto eff = make<talus::rheology::Hbp>(
      R"({"yield": "mohr_coulomb", "cohesion": 1, "friction_angle": 35, "regularisation": 1e6, "consistency": 0.126,
          "yield_pressure": "effective", "pore_fluid_density": 400})");
  const auto mu = mu_of(eff, {2.0}, {100.0});
  EXPECT_NEAR(mu[0], 0.126 + (1.0 + 60.0 * 0.70020753820970977) / 2.0, 1e-9);
}

TEST(Hbp, NotNewtonianSoTheStageRunsThreePasses) {
  const auto hbp = make<talus::rheology::Hbp>(R"({"consistency": 1})");
  EXPECT_FALSE(hbp.is_newtonian());
  EXPECT_TRUE(hbp.has_apparent_viscosity());
  const auto newt = make<talus::rheology::Newtonian>(R"({"viscosity": 1e-3})");
  EXPECT_TRUE(newt.is_newtonian());
}

}  // namespace
