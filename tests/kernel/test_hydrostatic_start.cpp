// The hydrostatic start (talus/hydrostatic.hpp): the pressure of the fluid
// above each particle, against rho g depth summed over stacked layers.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "talus/hydrostatic.hpp"

namespace talus {
namespace {

constexpr double g = 9.81;

// Particles filling a box on a lattice of spacing dp (half a spacing inside its faces), one density.
struct Fluid {
  std::vector<Vec3> x;
  std::vector<double> dp, rho;

  void box(Vec3 lo, Vec3 hi, double spacing, double density, int dim) {
    const int nx = static_cast<int>(std::lround((hi.x - lo.x) / spacing));
    const int ny = static_cast<int>(std::lround((hi.y - lo.y) / spacing));
    const int nz = dim == 3 ? static_cast<int>(std::lround((hi.z - lo.z) / spacing)) : 1;
    for (int k = 0; k < nz; ++k)
      for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
          x.push_back({lo.x + (i + 0.5) * spacing, lo.y + (j + 0.5) * spacing,
                       dim == 3 ? lo.z + (k + 0.5) * spacing : 0.0});
          dp.push_back(spacing);
          rho.push_back(density);
        }
  }
  std::vector<double> pressure(Vec3 gravity, int dim) const { return hydrostatic_pressure(x, dp, rho, gravity, dim); }
};

TEST(HydrostaticStart, OneBodyIsRhoGTimesTheDepthBelowItsSurface) {
  Fluid f;
  f.box({0.013, 0.0}, {0.413, 0.3}, 0.01, 1000.0, 2);  // columns not aligned with multiples of dp
  const auto p = f.pressure({0, -g, 0}, 2);
  for (std::size_t i = 0; i < p.size(); ++i) EXPECT_NEAR(p[i], 1000.0 * g * (0.3 - f.x[i].y), 1e-9 * 1000 * g);
}

TEST(HydrostaticStart, GravityAlongMinusZIn3D) {
  Fluid f;
  f.box({0, 0, 0}, {0.1, 0.06, 0.2}, 0.02, 1000.0, 3);
  const auto p = f.pressure({0, 0, -g}, 3);
  for (std::size_t i = 0; i < p.size(); ++i) EXPECT_NEAR(p[i], 1000.0 * g * (0.2 - f.x[i].z), 1e-9 * 1000 * g);
}

// Sediment (1922 kg/m^3) 0.1 m deep under 0.2 m of sea water (1029 kg/m^3), the water at `water_dp`.
void expect_water_over_sediment(double water_dp) {
  Fluid f;
  f.box({0, 0}, {0.2, 0.1}, 0.01, 1922.0, 2);
  f.box({0, 0.1}, {0.2, 0.3}, water_dp, 1029.0, 2);
  const auto p = f.pressure({0, -g, 0}, 2);
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double y = f.x[i].y;
    const double expected = y < 0.1 ? 1029.0 * g * 0.2 + 1922.0 * g * (0.1 - y) : 1029.0 * g * (0.3 - y);
    EXPECT_NEAR(p[i], expected, 1e-9 * expected) << "y = " << y;
  }
}

TEST(HydrostaticStart, ALayerUnderAnotherBodyCarriesItsWeight) { expect_water_over_sediment(0.01); }

TEST(HydrostaticStart, BodiesOfDifferentSpacingsStack) { expect_water_over_sediment(0.02); }

TEST(HydrostaticStart, ABodyAboveAnAirGapDoesNotLoadTheOneBelow) {
  Fluid f;
  f.box({0, 0}, {0.2, 0.1}, 0.01, 1000.0, 2);       // a pool
  f.box({0.05, 0.2}, {0.1, 0.25}, 0.01, 1000.0, 2);  // a block of water 0.1 m above it
  const auto p = f.pressure({0, -g, 0}, 2);
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double y = f.x[i].y;
    const double expected = 1000.0 * g * ((y < 0.1 ? 0.1 : 0.25) - y);
    EXPECT_NEAR(p[i], expected, 1e-9 * 1000 * g) << "y = " << y;
  }
}

TEST(HydrostaticStart, ZeroWithoutGravity) {
  Fluid f;
  f.box({0, 0}, {0.1, 0.1}, 0.01, 1000.0, 2);
  for (double p : f.pressure({0, 0, 0}, 2)) EXPECT_EQ(p, 0.0);
}

}  // namespace
}  // namespace talus
