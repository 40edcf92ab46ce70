// Buoyancy (issue 8, validation): a floating box settles at the Archimedes
// draft. (The fixed submerged block of share/scenes/buoyancy_fixed.json
// measures +20 % against rho g V at dp = 0.02 — five particles across the
// block — and is not part of the suite until a finer ladder shows where
// the excess goes; see the coupling issue's note.)
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "block_records.hpp"
#include "coupled_run.hpp"

using namespace coupling_test;

TEST(CouplingBuoyancy, FloatingBoxSettlesAtArchimedesDraft) {
  json scene = read_scene("buoyancy_floating.json");
  CoupledRun run(scene, "buoyancy_floating");
  const std::size_t k = run.block("box");
  const auto& b = *run.world().blocks;
  double z_lo = 1e300, z_hi = -1e300;
  for (const auto& v : b.shape[k].vertices) z_lo = std::min(z_lo, v.z), z_hi = std::max(z_hi, v.z);
  const double height = z_hi - z_lo;
  const double rho_block = b.mass[k] / b.volume[k];
  const double draft = rho_block / 1000.0 * height;
  const double water_level = scene["bodies"][0]["shape"]["box"]["max"][2].get<double>();
  ASSERT_EQ(run.run(), 0);
  const auto records = read_block_records(run.dir + "/out/buoyancy_floating.h5part", k);
  ASSERT_GT(records.size(), 10u);
  const double end = scene["time"]["end"].get<double>();
  double sum = 0.0;
  int n = 0;
  for (const auto& r : records)
    if (r.time > 0.6 * end) sum += r.position.z, ++n;
  // The fluid inside the box was removed at the start, so the free surface stays at the filled level.
  const double level = water_level;
  const double bottom = sum / n + z_lo;
  const double measured = level - bottom;
  std::printf("floating box: draft %.4f m (mean over the last 40%%), Archimedes %.4f m (%+.2f%%)\n", measured, draft,
              100.0 * (measured / draft - 1.0));
  EXPECT_NEAR(measured, draft, 0.02 * draft);
}
