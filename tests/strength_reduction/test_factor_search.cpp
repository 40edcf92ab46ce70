// The bracket-and-bisect search against a known threshold: it ends with the
// threshold inside a bracket no wider than the tolerance, within its trial
// budget, and says which end of a bracket that misses the threshold is wrong.
#include <gtest/gtest.h>

#include "factor_search.hpp"

using talus::strength_reduction::FactorSearch;

namespace {

int run(FactorSearch& s, double threshold) {
  int trials = 0;
  while (s.searching()) {
    s.record(s.next() > threshold);
    ++trials;
  }
  return trials;
}

}  // namespace

TEST(FactorSearch, BisectsToTheToleranceWithinItsBudget) {
  for (double threshold : {0.5001, 1.1201, 2.0, 3.9999}) {
    FactorSearch s(0.5, 4.0, 0.005);
    const int trials = run(s, threshold);
    EXPECT_EQ(s.phase(), FactorSearch::Phase::done) << threshold;
    EXPECT_LE(s.lo(), threshold);
    EXPECT_GE(s.hi(), threshold);
    EXPECT_LE(s.hi() - s.lo(), 0.005 * (1 + 1e-12));
    EXPECT_LE(trials, s.max_trials());
    EXPECT_NEAR(s.safety_factor(), threshold, 0.0025 + 1e-12);
  }
  EXPECT_EQ(FactorSearch(0.5, 4.0, 0.005).max_trials(), 2 + 10);  // 3.5 / 2^10 = 0.0034 <= 0.005 < 3.5 / 2^9
}

TEST(FactorSearch, ABracketThatMissesTheThresholdSaysWhichEnd) {
  FactorSearch low(1.5, 4.0, 0.01);
  run(low, 1.2);
  EXPECT_EQ(low.phase(), FactorSearch::Phase::fails_at_lower);
  FactorSearch high(0.5, 1.0, 0.01);
  run(high, 1.2);
  EXPECT_EQ(high.phase(), FactorSearch::Phase::holds_at_upper);
}
