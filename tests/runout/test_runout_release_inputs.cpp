// Release inputs the strength-reduction hand-off writes: a vertical release
// thickness (a column over the cell), and a basal-shear raster each particle
// resists with until it first moves.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <numbers>

#include "esri_ascii.hpp"
#include "runout_world.hpp"

using namespace talus;
using namespace talus::runout;
using talus::runout::test::RunoutWorld;

namespace {

constexpr double dp = 0.2;

// A periodic frictionless layer on a 30 degree plane.
std::unique_ptr<RunoutWorld> layer(const std::string& extra) {
  auto w = std::make_unique<RunoutWorld>(Vec3{0.0, 0.0, 0.0}, Vec3{12 * dp, 12 * dp, 0.0}, dp, 1.3,
                                         std::array<bool, 3>{true, true, false});
  const int m = w->add_material("debris", 2000.0, nullptr);
  w->fill_box({0.0, 0.0, 0.0}, {12 * dp, 12 * dp, 0.0}, m);
  w->make_stage(R"({"terrain": {"plane": {"slope": 30}}, "release_thickness": 2.0)" + extra + "}", 1.0);
  return w;
}

// A uniform raster over the layer's cells.
std::string uniform_raster(const std::string& name, double value) {
  Grid g;
  g.cell = dp;
  g.x0 = g.y0 = 0.5 * dp;
  g.resize(12, 12, value);
  const std::string path = (std::filesystem::temp_directory_path() / name).string();
  write_esri_ascii(path, g);
  return path;
}

}  // namespace

TEST(RunoutRelease, VerticalThicknessIsAColumnOverTheCell) {
  auto normal = layer("");
  auto vertical = layer(R"(, "thickness_measured": "vertical")");
  const double cos30 = std::cos(std::numbers::pi / 6.0);
  EXPECT_NEAR(normal->world.fluid.scalar("volume")[0], 2.0 / cos30 * dp * dp, 1e-12);
  EXPECT_NEAR(vertical->world.fluid.scalar("volume")[0], 2.0 * dp * dp, 1e-12);
}

TEST(RunoutRelease, LimitStateShearHoldsTheMassUntilItIsExceeded) {
  // Frictionless, a 2 m layer (slope-normal) on 30 degrees needs rho g h sin 30 = 19.6 kPa to stay.
  const double needed = 2000.0 * 9.81 * 2.0 * 0.5;
  auto held = layer(R"(, "basal_shear_raster": ")" + uniform_raster("held.asc", 1.2 * needed) + "\"");
  held->run_to(1.0);
  for (const Vec3& v : held->world.fluid.vector("velocity")) ASSERT_EQ(v, (Vec3{}));
  for (const double tau : held->world.fluid.scalar("initial_basal_shear")) EXPECT_NEAR(tau, 1.2 * needed, 1e-6);

  auto released = layer(R"(, "basal_shear_raster": ")" + uniform_raster("weak.asc", 0.5 * needed) + "\"");
  released->run_to(1.0);
  // It moved, and once moving it lost the limit-state shear: frictionless, it accelerates at g sin 30.
  for (const double tau : released->world.fluid.scalar("initial_basal_shear")) EXPECT_EQ(tau, 0.0);
  const Vec3 v = released->world.fluid.vector("velocity")[0];
  const double speed = std::sqrt(norm2(v) + std::pow(v.x * std::tan(std::numbers::pi / 6.0), 2));
  std::printf("after 1 s: %.4f m/s (frictionless from rest: at most g sin 30 t = 4.905)\n", speed);
  EXPECT_GT(speed, 0.5 * 9.81 * 0.5);
  EXPECT_LE(speed, 9.81 * 0.5 * 1.0 + 1e-9);
}
