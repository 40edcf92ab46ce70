// Rotation invariance of a whole run: a 2D dam break in a tank whose open
// face changes side, run upright and turned by 90 and 180 degrees (domain,
// tank, column and gravity turned together), gives the same front history
// and the same particle states, turned back, to round-off. The box lattices
// are mirror-exact (talus/geometry.hpp), so what differs is only the order
// in which the neighbour sums add up. The tank and the column are not whole
// numbers of spacings wide: a lattice counted from the minimum corner would
// put the turned walls elsewhere.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "sph_world.hpp"

namespace {

using talus::Vec3;
using sph_test::SphWorld;

// Quarter turns counter-clockwise about the origin: (x, y) -> (-y, x).
Vec3 turn(const Vec3& p, int quarters) {
  Vec3 q = p;
  for (int k = 0; k < quarters; ++k) q = {-q.y, q.x, 0.0};
  return q;
}

// The axis-aligned box spanned by two turned corners.
void turned_box(Vec3 lo, Vec3 hi, int quarters, Vec3& out_lo, Vec3& out_hi) {
  const Vec3 a = turn(lo, quarters), b = turn(hi, quarters);
  out_lo = {std::min(a.x, b.x), std::min(a.y, b.y), 0.0};
  out_hi = {std::max(a.x, b.x), std::max(a.y, b.y), 0.0};
}

// The open face +y of the upright tank, turned.
std::string open_face(int quarters) {
  const char* faces[] = {"+y", "-x", "-y", "+x"};
  return faces[quarters % 4];
}

struct History {
  std::vector<double> front;  // the leading edge along the turned +x, each step
  std::vector<Vec3> x, v;     // final positions and velocities, turned back, sorted by position at the start
};

History dam_break(int quarters, int steps, const std::string& walls = "{}") {
  const double dp = 0.02;
  Vec3 lo, hi;
  turned_box({0, 0, 0}, {0.81, 0.6, 0}, quarters, lo, hi);  // 40.5 spacings wide: the lattice is fitted
  SphWorld s(2, lo, hi, dp);
  s.world.gravity = turn({0, -9.81, 0}, quarters);
  const int water = s.water(20.0);
  Vec3 clo, chi;
  turned_box({0, 0, 0}, {0.21, 0.4, 0}, quarters, clo, chi);  // 10.5 spacings
  s.fluid_box(water, clo, chi, true);
  s.dbc_wall("{\"box_walls\": {\"min\": " + SphWorld::vec(lo, 2) + ", \"max\": " + SphWorld::vec(hi, 2) +
                 ", \"open\": [\"" + open_face(quarters) + "\"]}}",
             water, "", walls);
  s.make_stage();
  // Particle k of the upright run is the one that starts where the turned run's particle starts, turned back.
  const auto start = s.world.fluid.position();
  std::vector<std::pair<Vec3, std::uint64_t>> by_start;
  const auto ids = s.world.fluid.ids();
  for (std::size_t i = 0; i < start.size(); ++i) by_start.push_back({turn(start[i], 4 - quarters), ids[i]});
  auto before = [](const auto& a, const auto& b) {
    const double dx = a.first.x - b.first.x;
    return std::abs(dx) > 1e-9 ? dx < 0 : a.first.y < b.first.y;
  };
  std::sort(by_start.begin(), by_start.end(), before);

  History r;
  for (int n = 0; n < steps; ++n) {
    s.step();
    double front = -1e300;
    for (const Vec3& p : s.world.fluid.position()) front = std::max(front, turn(p, 4 - quarters).x);
    r.front.push_back(front);
  }
  const auto x = s.world.fluid.position();
  const auto v = s.world.fluid.vector("velocity");
  const auto now = s.world.fluid.ids();
  for (const auto& [p0, id] : by_start) {
    const std::size_t i = static_cast<std::size_t>(std::find(now.begin(), now.end(), id) - now.begin());
    r.x.push_back(turn(x[i], 4 - quarters));
    r.v.push_back(turn(v[i], 4 - quarters));
  }
  return r;
}

void expect_turned_runs_agree(const std::string& walls) {
  const int steps = 300;
  const History upright = dam_break(0, steps, walls);
  ASSERT_GT(upright.front.back(), upright.front.front() + 0.02);  // the surge has moved: a flow, not a rest state
  for (int quarters : {1, 2}) {
    const History turned = dam_break(quarters, steps, walls);
    ASSERT_EQ(turned.front.size(), upright.front.size());
    double worst_front = 0.0, worst_x = 0.0, worst_v = 0.0, speed = 0.0;
    for (std::size_t n = 0; n < upright.front.size(); ++n)
      worst_front = std::max(worst_front, std::abs(turned.front[n] - upright.front[n]) / upright.front[n]);
    ASSERT_EQ(turned.x.size(), upright.x.size());
    for (std::size_t k = 0; k < upright.x.size(); ++k) {
      worst_x = std::max(worst_x, talus::norm(turned.x[k] - upright.x[k]));
      worst_v = std::max(worst_v, talus::norm(turned.v[k] - upright.v[k]));
      speed = std::max(speed, talus::norm(upright.v[k]));
    }
    std::printf("  %s walls, %d x 90 deg: front %.2e relative, positions %.2e m, velocities %.2e of the largest speed\n",
                walls.c_str(), quarters, worst_front, worst_x, worst_v / speed);
    EXPECT_LT(worst_front, 1e-9) << quarters;
    EXPECT_LT(worst_x, 1e-9 * 0.02) << quarters;  // a billionth of a spacing
    EXPECT_LT(worst_v, 1e-9 * speed) << quarters;
  }
}

TEST(RotationInvariance, TurnedDamBreakGivesTheSameFrontAndStates) { expect_turned_runs_agree("{}"); }

// mDBC: the ghost nodes are mirrored across the turned faces and corners alike.
TEST(RotationInvariance, TurnedDamBreakOnMdbcWallsGivesTheSameFrontAndStates) {
  expect_turned_runs_agree(R"({"method": "mdbc"})");
}

}  // namespace
