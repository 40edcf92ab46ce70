#include <gtest/gtest.h>

#include "cohesion.hpp"

namespace {

struct Sums {
  talus::Vec3 acc;
};

// One pair, both ways: the hand value, and equal and opposite forces.
TEST(Cohesion, PairForceIsAntisymmetric) {
  const double mass[2] = {2.0, 3.0};
  const example::CohesionPair term{mass, 0.5};
  talus::sph::Pair ij;
  ij.j = 1;
  ij.dx = {0.1, -0.2, 0.05};
  ij.w = 4.0;
  talus::sph::Pair ji = ij;
  ji.j = 0;
  ji.dx = ij.dx * -1.0;
  Sums si, sj;
  term.pair(ij, si);
  term.pair(ji, sj);
  for (int a = 0; a < 3; ++a) {
    EXPECT_DOUBLE_EQ(si.acc[a], -0.5 * 3.0 * 4.0 * ij.dx[a]);
    EXPECT_NEAR(mass[0] * si.acc[a] + mass[1] * sj.acc[a], 0.0, 1e-15);
  }
}

}  // namespace
