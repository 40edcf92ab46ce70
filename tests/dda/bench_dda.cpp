// A few thousand blocks settling in a box: contact points per second and the
// share of the step spent in detection, contact forces and integration.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "dda_test_world.hpp"

using talus::dda::test::BlockScene;

namespace {

const char* joint = R"({"type": "penalty_coulomb", "normal_stiffness": 1e7, "friction_angle": 30, "damping_ratio": 0.2})";

std::string box(double x0, double y0, double z0, double x1, double y1, double z1) {
  char buf[200];
  std::snprintf(buf, sizeof buf, R"({"box": {"min": [%.9g, %.9g, %.9g], "max": [%.9g, %.9g, %.9g]}})", x0, y0, z0, x1, y1,
                z1);
  return buf;
}

std::string cube(double x, double y, double z, double a, double tilt) {
  // A cube of edge a centred at (x, y, z), tilted by `tilt` rad about x (as a polyhedron).
  const double c = std::cos(tilt), s = std::sin(tilt), h = 0.5 * a;
  std::string v = "[";
  for (int k = 0; k < 8; ++k) {
    const double px = (k & 1) ? h : -h, py = (k & 2) ? h : -h, pz = (k & 4) ? h : -h;
    char buf[100];
    std::snprintf(buf, sizeof buf, "%s[%.12g,%.12g,%.12g]", k ? "," : "", x + px, y + c * py - s * pz, z + s * py + c * pz);
    v += buf;
  }
  return R"({"polyhedron": {"vertices": )" + v +
         R"(], "faces": [[0,2,3,1],[4,5,7,6],[0,1,5,4],[2,6,7,3],[0,4,6,2],[1,3,7,5]]}})";
}

// n x n columns of `layers` cubes (edge 0.2 m, gaps 2 cm, small random tilts)
// in a box with a floor and four walls.
void build(BlockScene& s, int n, int layers) {
  const double a = 0.2, pitch = 0.22, size = n * pitch;
  auto fixed = [&](const std::string& name, const std::string& shape) {
    s.add_block(R"({"name": ")" + name + R"(", "kind": "block", "density": 2500, "fixed": true, "shape": )" + shape + "}",
                joint);
  };
  fixed("floor", box(-0.5, -0.5, -0.3, size + 0.5, size + 0.5, 0));
  fixed("wall-x0", box(-0.5, -0.5, 0, -0.1, size + 0.5, 3));
  fixed("wall-x1", box(size + 0.1, -0.5, 0, size + 0.5, size + 0.5, 3));
  fixed("wall-y0", box(-0.1, -0.5, 0, size + 0.1, -0.1, 3));
  fixed("wall-y1", box(-0.1, size + 0.1, 0, size + 0.1, size + 0.5, 3));
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> tilt(-0.2, 0.2);
  int k = 0;
  for (int l = 0; l < layers; ++l)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        s.add_block(R"({"name": "b)" + std::to_string(k++) + R"(", "kind": "block", "density": 2500, "shape": )" +
                        cube((i + 0.5) * pitch, (j + 0.5) * pitch, 0.15 + l * 0.25, a, tilt(rng)) + "}",
                    joint);
}

void BM_BlocksSettling(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0)), layers = static_cast<int>(state.range(1));
  BlockScene s;
  build(s, n, layers);
  auto& stage = s.start();
  s.run_steps(2000);  // let the columns fall onto each other: contacts everywhere
  const auto before = stage.timing();
  for (auto _ : state) s.run_steps(10);
  const auto& t = stage.timing();
  const double detection = t.detection - before.detection, forces = t.forces - before.forces,
               integration = t.integration - before.integration, total = detection + forces + integration;
  state.counters["blocks"] = static_cast<double>(s.blocks().size());
  state.counters["contacts"] = static_cast<double>(stage.contacts().size());
  state.counters["contacts/s"] =
      benchmark::Counter(static_cast<double>(t.contact_points - before.contact_points), benchmark::Counter::kIsRate);
  state.counters["steps/s"] = benchmark::Counter(static_cast<double>(t.steps - before.steps), benchmark::Counter::kIsRate);
  state.counters["detection %"] = 100.0 * detection / total;
  state.counters["forces %"] = 100.0 * forces / total;
  state.counters["integration %"] = 100.0 * integration / total;
}

}  // namespace

BENCHMARK(BM_BlocksSettling)->Args({8, 8})->Args({16, 8})->Args({16, 16})->Unit(benchmark::kMillisecond);
