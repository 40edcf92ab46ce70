// Speed of the wcsph stage on the 3D dam break of the DualSPHysics 01_DamBreak
// kind (issue 3): a 0.4 x 0.67 x 0.3 m column in a 1.6 x 0.67 x 0.4 m tank with
// one layer of dynamic boundary particles, open at the top, and DualSPHysics'
// settings: cubic spline, h = sqrt(3) dp (~174 neighbours), Verlet, artificial
// viscosity 0.1, density diffusion 0.1, c0 = 20 sqrt(g 0.3).
//   bench_wcsph --benchmark_filter='/85/'    dp = 0.0085 m, ~171 000 particles
// Arguments: dp in 1e-4 m, OpenMP threads. Counters: particles (fluid + wall),
// particle_steps/s, pairs/s (particle-neighbour evaluations, fluid-fluid,
// fluid-wall and wall-fluid), bytes/particle (peak resident memory of the run
// above the process's own, which holds the libraries), field_bytes/particle
// (the particle fields alone; the rest is stage scratch and neighbour grids).
// Reference (DualSPHysics 5.4 CPU, 2 threads, dp = 0.0085): 0.36 M particle-steps/s,
// ~63 M particle-neighbour evaluations/s, ~131 bytes per particle.
#include <benchmark/benchmark.h>
#include <omp.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "sph_world.hpp"

namespace {

// Resident memory from /proc/self/status: "VmHWM:" (peak) or "VmRSS:" (now).
double resident_bytes(const std::string& key) {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind(key, 0) == 0) return std::stod(line.substr(key.size())) * 1024.0;
  return 0.0;
}

// Restarts the peak count (Linux >= 4.0), so each benchmark sees its own peak.
void reset_peak_resident() { std::ofstream("/proc/self/clear_refs") << "5"; }

// Bytes of the particle stores' fields (fluid and wall), without the stage's
// scratch arrays, the neighbour grids or the process itself.
double store_bytes(const talus::ParticleStore& store) {
  double bytes = 0.0;
  for (const talus::FieldInfo& f : store.fields()) {
    const double each = f.type == talus::FieldType::vector    ? sizeof(talus::Vec3)
                        : f.type == talus::FieldType::integer ? sizeof(std::int32_t)
                                                              : 8.0;  // scalar (double) or id (uint64)
    bytes += each * static_cast<double>(store.size());
  }
  return bytes;
}

void dam_break_3d(benchmark::State& state) {
  const double dp = state.range(0) * 1e-4;
  omp_set_num_threads(static_cast<int>(state.range(1)));
  reset_peak_resident();
  const double baseline = resident_bytes("VmRSS:");  // the process before the world exists
  sph_test::SphWorld s(3, {0, 0, 0}, {1.6, 0.67, 0.4}, dp, 1.7320508, "cubic_spline");
  const int water = s.water(20.0 * std::sqrt(9.81 * 0.3));
  s.fluid_box(water, {0, 0, 0}, {0.4, 0.67, 0.3}, true);
  s.dbc_wall(R"({"box_walls": {"min": [0, 0, 0], "max": [1.6, 0.67, 0.4], "open": ["+z"]}})", -1, R"(, "layers": 1)");
  auto& stage = s.make_stage(
      R"({"integrator": "verlet", "viscosity": "artificial", "alpha": 0.1, "density_diffusion": "fourtakas", "delta": 0.1})");
  for (int k = 0; k < 3; ++k) s.step();  // let the column start moving
  const double particles = static_cast<double>(s.world.fluid.size() + s.world.boundary.size());
  const std::uint64_t pairs0 = stage.pair_evaluations();
  std::int64_t steps = 0;
  for (auto _ : state) {
    s.step();
    ++steps;
  }
  const double pairs = static_cast<double>(stage.pair_evaluations() - pairs0);
  state.counters["particles"] = particles;
  state.counters["fluid"] = static_cast<double>(s.world.fluid.size());
  state.counters["particle_steps/s"] = benchmark::Counter(particles * steps, benchmark::Counter::kIsRate);
  state.counters["pairs/s"] = benchmark::Counter(pairs, benchmark::Counter::kIsRate);
  state.counters["neighbours"] = pairs / (particles * steps);
  state.counters["bytes/particle"] = (resident_bytes("VmHWM:") - baseline) / particles;
  state.counters["field_bytes/particle"] = (store_bytes(s.world.fluid) + store_bytes(s.world.boundary)) / particles;
  state.counters["sim_time"] = s.world.time;
}

}  // namespace

BENCHMARK(dam_break_3d)
    ->ArgNames({"dp_1e-4m", "threads"})
    ->Args({200, 1})
    ->Args({200, 2})
    ->Args({120, 1})
    ->Args({120, 2})
    ->Args({85, 1})
    ->Args({85, 2})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(5.0);
