// Action = reaction between the fluid and a block, for both coupling models:
// a blob of water thrown at a free block in zero gravity, no walls. The
// fluid's momentum change must equal minus the block's momentum change plus
// the impulse still owed (the force committed for the next DDA step x dt),
// to round-off. A restart continues that bookkeeping bit for bit. Also: the
// pipeline order check names /pipeline.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "coupled_run.hpp"
#include "talus/error.hpp"

using namespace coupling_test;

namespace {

json blob_scene(const std::string& boundary, double speed = 2.0) {
  return json::parse(R"({
    "talus": 1,
    "description": "momentum exchange: a 0.16 m cube of water at 2 m/s hits a free 0.1 m block, zero gravity",
    "domain": { "dim": 3, "min": [-0.5, -0.5, -0.5], "max": [1.0, 0.5, 0.5] },
    "gravity": [0, 0, 0],
    "kernel": { "type": "wendland_c2", "h_over_dp": 1.3 },
    "materials": { "water": { "density": 1000, "eos": { "type": "tait", "c0": 20, "gamma": 7 } } },
    "bodies": [
      { "name": "blob", "kind": "fluid", "material": "water", "dp": 0.02, "velocity": [)" + std::to_string(speed) + R"(, 0, 0],
        "shape": { "box": { "min": [-0.2, -0.08, -0.08], "max": [-0.04, 0.08, 0.08] } } },
      { "name": "rock", "kind": "block", "density": 1500,
        "shape": { "box": { "min": [0.0, -0.05, -0.05], "max": [0.1, 0.05, 0.05] } },
        "boundary": { "type": ")" + boundary + R"(" },
        "contact": { "type": "penalty_coulomb", "normal_stiffness": 1e6, "friction_angle": 30 } }
    ],
    "pipeline": [ { "stage": "dda", "subcycle": true }, { "stage": "wcsph", "alpha": 0.05 } ],
    "time": { "end": 0.06, "dt_max": 1e-4 }
  })");
}

void check_exchange(const std::string& boundary, json scene = json()) {
  if (scene.is_null()) scene = blob_scene(boundary);
  CoupledRun run(scene, "momentum_" + boundary);
  talus::World& w = run.world();
  const std::size_t k = run.block("rock");
  const double m_block = w.blocks->mass[k];
  const talus::Vec3 p_fluid0 = fluid_momentum(w), v_block0 = w.blocks->velocity[k];
  const std::size_t n0 = w.fluid.size();
  ASSERT_EQ(run.run(), 0);
  ASSERT_EQ(w.fluid.size(), n0);  // nothing left the domain
  const talus::Vec3 d_fluid = fluid_momentum(w) - p_fluid0;
  const talus::Vec3 d_block = (w.blocks->velocity[k] - v_block0) * m_block;
  const double dt = scene["time"]["dt_max"].get<double>();   // the step, constant: dt_max is below the CFL bound
  const talus::Vec3 owed = w.blocks->external_force[k] * dt;  // delivered in the next step
  // The block really was hit: it took a sizeable share of the blob's 8.2 kg m/s.
  EXPECT_GT(d_block.x, 0.5) << boundary;
  const talus::Vec3 balance = d_fluid + d_block + owed;
  std::printf("%s: fluid dP = (%.6g, %.6g, %.6g), block dP = (%.6g, %.6g, %.6g), owed (%.3g, %.3g, %.3g), "
              "balance (%.3g, %.3g, %.3g) kg m/s\n",
              boundary.c_str(), d_fluid.x, d_fluid.y, d_fluid.z, d_block.x, d_block.y, d_block.z, owed.x, owed.y,
              owed.z, balance.x, balance.y, balance.z);
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(balance[a], 0.0, 1e-9) << boundary << " axis " << a;
  std::printf("%s: %llu fluid particles were put back on the block's faces\n", boundary.c_str(),
              static_cast<unsigned long long>(w.wall_crossings));
}

}  // namespace

TEST(CouplingMomentum, BlockParticlesActionEqualsReaction) { check_exchange("block_particles"); }

// A fast blob on a block of one layer: fluid gets inside and is put back on
// its faces; the momentum that takes goes to the block.
TEST(CouplingMomentum, FluidPutBackOnABlockGivesTheBlockItsMomentum) {
  json scene = blob_scene("block_particles", 30.0);
  scene["bodies"][1]["boundary"]["layers"] = 1;
  scene["time"]["end"] = 0.006;
  scene["time"]["dt_max"] = 1e-5;
  CoupledRun probe(scene, "momentum_put_back_probe");
  ASSERT_EQ(probe.run(), 0);
  ASSERT_GT(probe.world().wall_crossings, 0u) << "the blob must get inside the block for this test to mean anything";
  check_exchange("block_particles", scene);
}

TEST(CouplingMomentum, RepulsionActionEqualsReaction) { check_exchange("block_repulsion"); }

// Refused by the host from the stages' declared parts, before any stage sets up.
TEST(CouplingMomentum, FluidStageBeforeDdaIsAnInputErrorNamingThePipeline) {
  auto expect_refused = [](const char* pipeline, const std::string& name, const std::string& words) {
    json scene = blob_scene("block_particles");
    scene["pipeline"] = json::parse(pipeline);
    try {
      CoupledRun run(scene, name);
      ADD_FAILURE() << name << ": expected an InputError";
    } catch (const talus::InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(words), std::string::npos) << what;
    }
  };
  expect_refused(R"([ { "stage": "wcsph" }, { "stage": "dda", "subcycle": true } ])", "momentum_order",
                 "/pipeline/0: stage 'wcsph' needs the blocks that stage 'dda' (/pipeline/1) builds");
  expect_refused(R"([ { "stage": "wcsph" } ])", "momentum_no_dda",
                 "/pipeline/0: stage 'wcsph' needs blocks, which no stage of the pipeline builds");
}

namespace {

// A fixed block held under still water in a tank periodic in x and y; `x0` is
// the block's lower x. The period (0.48 m) and the shift are whole numbers of dp.
json periodic_scene(double x0) {
  json scene = json::parse(R"({
    "talus": 1,
    "description": "a submerged fixed block, periodic in x and y, to compare the fluid's force and torque on it away from and across the periodic boundary",
    "domain": { "dim": 3, "min": [0, 0, 0], "max": [0.48, 0.16, 0.3], "periodic": ["x", "y"] },
    "gravity": [0, 0, -9.81],
    "kernel": { "type": "wendland_c2", "h_over_dp": 1.3 },
    "materials": { "water": { "density": 1000, "eos": { "type": "tait", "c0": 20, "gamma": 7 } } },
    "bodies": [
      { "name": "water", "kind": "fluid", "material": "water", "dp": 0.02, "hydrostatic": true,
        "shape": { "box": { "min": [0, 0, 0], "max": [0.48, 0.16, 0.2] } } },
      { "name": "floor", "kind": "wall", "dp": 0.02, "boundary": { "type": "dynamic_particles" },
        "shape": { "box_walls": { "min": [0, 0, 0], "max": [0.48, 0.16, 0.3],
                                  "open": ["+z", "-x", "+x", "-y", "+y"] } } },
      { "name": "rock", "kind": "block", "density": 2500, "fixed": true,
        "shape": { "box": { "min": [0, 0.04, 0.07], "max": [0.12, 0.12, 0.13] } },
        "boundary": { "type": "block_particles" },
        "contact": { "type": "penalty_coulomb", "normal_stiffness": 1e6, "friction_angle": 30 } }
    ],
    "pipeline": [ { "stage": "dda", "subcycle": true }, { "stage": "wcsph", "alpha": 0.05 } ],
    "time": { "end": 1.0, "dt_max": 1e-4, "max_steps": 5 }
  })");
  scene["bodies"][2]["shape"]["box"]["min"][0] = x0;
  scene["bodies"][2]["shape"]["box"]["max"][0] = x0 + 0.12;
  return scene;
}

}  // namespace

// A block straddling a periodic boundary feels the same force and torque as
// the same block away from it: the lever arm x_i - X and the fluid the block
// sees are taken at the minimum image (block_pass.hpp; before, the fluid
// across the boundary was skipped and its lever arm was off by the period).
TEST(CouplingMomentum, BlockAcrossAPeriodicBoundaryFeelsTheSameForceAndTorque) {
  CoupledRun inside(periodic_scene(0.18), "periodic_inside");
  CoupledRun across(periodic_scene(-0.06), "periodic_across");  // 0.24 m = half the period further
  ASSERT_EQ(inside.run(), 0);
  ASSERT_EQ(across.run(), 0);
  const auto& a = *inside.world().blocks;
  const auto& b = *across.world().blocks;
  const std::size_t ka = inside.block("rock"), kb = across.block("rock");
  const talus::Vec3 fa = a.external_force[ka], fb = b.external_force[kb];
  const talus::Vec3 ta = a.external_torque[ka], tb = b.external_torque[kb];
  std::printf("inside: F = (%.6g, %.6g, %.6g) N, T = (%.3g, %.3g, %.3g) N m; across: F = (%.6g, %.6g, %.6g) N, "
              "T = (%.3g, %.3g, %.3g) N m\n",
              fa.x, fa.y, fa.z, ta.x, ta.y, ta.z, fb.x, fb.y, fb.z, tb.x, tb.y, tb.z);
  // The water holds the block up with about rho g V = 5.6 N.
  EXPECT_GT(fa.z, 2.0);
  // Same configuration up to a translation by whole cells: equal to round-off (summation order differs). A
  // lever arm off by the 0.48 m period on half the fluid would give |T_y| ~ 0.24 m x 2.8 N = 0.7 N m.
  for (int d = 0; d < 3; ++d) {
    EXPECT_NEAR(fb[d], fa[d], 1e-6 * std::abs(fa.z)) << "force axis " << d;
    EXPECT_NEAR(tb[d], ta[d], 1e-6 * std::abs(fa.z) * 0.1) << "torque axis " << d;
  }
}

// The walls' initial state comes from the still water around them (pressure
// extrapolation): each wall and block particle starts at the hydrostatic
// pressure of its depth. The block is bound first here, and its bind removes
// the water inside it and moves the water against it: the floor, bound next,
// and the block itself must read the water as it is then, not as it was
// filled (a grid of the filled water gives them other particles' pressures).
TEST(CouplingMomentum, WallsAndBlockStartAtTheHydrostaticPressureOfTheWaterAroundThem) {
  json scene = periodic_scene(0.18);
  std::swap(scene["bodies"][1], scene["bodies"][2]);  // water, rock, floor: the block binds first
  scene["time"]["max_steps"] = 1;
  CoupledRun run(scene, "initial_wall_pressure");
  const talus::World& w = run.world();
  // The water's own pressure against depth, p = a + b z, by least squares.
  const auto xf = w.fluid.position();
  const auto pf = w.fluid.scalar("pressure");
  double sz = 0, sp = 0, szz = 0, szp = 0;
  const double n = static_cast<double>(xf.size());
  for (std::size_t i = 0; i < xf.size(); ++i) {
    sz += xf[i].z;
    sp += pf[i];
    szz += xf[i].z * xf[i].z;
    szp += xf[i].z * pf[i];
  }
  const double b = (n * szp - sz * sp) / (n * szz - sz * sz), a = (sp - b * sz) / n;
  EXPECT_NEAR(b, -1000.0 * 9.81, 0.01 * 1000.0 * 9.81);  // rho0 g
  // Every wall or block particle with water in its support: within 1 % of the
  // pressure at the bottom (the extrapolation is exact for a linear field; the
  // water's density differs from rho0 by p/c^2, below 0.5 %).
  const auto xb = w.boundary.position();
  const auto pb = w.boundary.scalar("pressure");
  const auto body = w.boundary.body();
  const double tolerance = 0.01 * a;
  int rock = 0, floor = 0, bad = 0;
  for (std::size_t k = 0; k < xb.size(); ++k) {
    if (!(pb[k] > 0.0)) continue;  // no water within reach (below the floor's first layer)
    const bool is_rock = w.bodies[body[k]].name == "rock";
    (is_rock ? rock : floor) += 1;
    const double want = a + b * xb[k].z;
    if (std::abs(pb[k] - want) > tolerance && ++bad <= 5)
      ADD_FAILURE() << (is_rock ? "block" : "floor") << " particle at z = " << xb[k].z << ": p = " << pb[k]
                    << " Pa, the water's " << want << " Pa";
  }
  EXPECT_GT(rock, 50);
  EXPECT_GT(floor, 50);
}

namespace {

std::vector<std::filesystem::path> checkpoints_in(const std::string& dir) {
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    if (e.path().extension() == ".checkpoint") files.push_back(e.path());
  std::ranges::sort(files);
  return files;
}

std::string bytes_of(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// A run continued from a checkpoint ends bit for bit where the uninterrupted
// run ends. The time step follows the CFL bound, so it changes from step to
// step and the impulse the ledger still owes the block is never zero: without
// the ledger in the checkpoint the restarted block gets a slightly different
// force (1e-7 N on the block impact of tests/mpi).
void check_restart(const std::string& boundary) {
  json scene = blob_scene(boundary);
  scene["time"].erase("dt_max");
  scene["checkpoint"] = {{"every", 0.03}, {"keep", 5}};
  CoupledRun whole(scene, "restart_whole_" + boundary);
  ASSERT_EQ(whole.run(), 0);
  const auto ends = checkpoints_in(whole.dir + "/out");
  ASSERT_EQ(ends.size(), 2u) << boundary;
  CoupledRun resumed(scene, "restart_resumed_" + boundary);
  talus::RunOptions o;
  o.output_directory = resumed.dir + "/out";
  o.quiet = true;
  o.restart = ends.front().string();
  ASSERT_EQ(resumed.sim->run(o), 0);
  const auto again = checkpoints_in(resumed.dir + "/out");
  ASSERT_FALSE(again.empty()) << boundary;
  const std::string step = ends.back().filename().string(), step_again = again.back().filename().string();
  ASSERT_EQ(step.substr(step.rfind('_')), step_again.substr(step_again.rfind('_'))) << boundary;
  EXPECT_TRUE(bytes_of(ends.back()) == bytes_of(again.back()))
      << boundary << ": the restarted run ends elsewhere than the uninterrupted one";
}

}  // namespace

TEST(CouplingMomentum, BlockParticlesRunRestartsBitForBit) { check_restart("block_particles"); }
TEST(CouplingMomentum, RepulsionRunRestartsBitForBit) { check_restart("block_repulsion"); }
