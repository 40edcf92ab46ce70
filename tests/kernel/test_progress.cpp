// The progress line's ETA: the pace since this process started, from the
// simulated time it started at (a resumed run starts part-way).
#include <gtest/gtest.h>

#include "progress.hpp"

namespace talus {
namespace {

TEST(Progress, EtaFromThePaceSinceThisProcessStarted) {
  // 10 s of wall time took a fresh run from t = 0 to 1 of 4: 30 s to go.
  EXPECT_DOUBLE_EQ(eta_seconds(10.0, 0.0, 1.0, 4.0), 30.0);
  // Resumed at t = 2.7, 10 s took it to 3.0 of 4: 33.3 s to go (from 0 it would say 3.3 s).
  EXPECT_NEAR(eta_seconds(10.0, 2.7, 3.0, 4.0), 33.333, 1e-3);
  // Nothing done yet: unknown.
  EXPECT_LT(eta_seconds(1.0, 2.0, 2.0, 4.0), 0.0);
}

}  // namespace
}  // namespace talus
