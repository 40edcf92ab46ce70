// Writes a sample output set with all three writers from a hand-built 3D
// water column (and two blocks), and reports how long each writer takes per
// frame. Used by the Python tool tests (preview, plot_probes, pvpython_check)
// and for timings:
//   writers_sample OUTPUT_FOLDER [PARTICLES=20000] [FRAMES=5] [--no-sync]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>

#include "hdf5_writer.hpp"
#include "probes_writer.hpp"
#include "vtu_writer.hpp"
#include "world_fixture.hpp"

using namespace talus;

namespace {
void advance(World& w, int frame) {
  // A collapsing column: x stretches, z drops, a travelling pressure pulse.
  auto x = w.fluid.position();
  auto v = w.fluid.vector("velocity");
  auto p = w.fluid.scalar("pressure");
  const double t = 0.05 * frame;
  for (std::size_t i = 0; i < w.fluid.size(); ++i) {
    const double s = 1.0 + 0.3 * t;
    v[i] = {0.3 * x[i].x, 0.0, -0.3 * x[i].z};
    x[i].x *= s;
    x[i].z /= s;
    p[i] = 1000.0 * 9.81 * std::max(0.0, 0.3 - x[i].z) * (1.0 + 0.2 * std::sin(10.0 * x[i].x - 5.0 * t));
  }
  w.time = t;
  w.step = 100u * frame;
  if (w.blocks) w.blocks->position[0] += Vec3{0.02, 0.0, -0.01};
}
}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s OUTPUT_FOLDER [PARTICLES] [FRAMES] [--no-sync]\n", argv[0]);
    return 2;
  }
  const std::string out = argv[1];
  const long particles = argc > 2 ? std::atol(argv[2]) : 20000;
  const int frames = argc > 3 ? std::atoi(argv[3]) : 5;
  const bool sync = !(argc > 4 && std::strcmp(argv[4], "--no-sync") == 0);
  std::filesystem::create_directories(out);

  // A column 2a x a x 2a (x, y, z) of n particles: n = 4 a^3 / dp^3.
  const int ny = std::max(2, static_cast<int>(std::cbrt(particles / 4.0)));
  const double dp = 0.3 / (2 * ny);
  World w;
  w.lo = {0, 0, 0};
  w.hi = {1.6, 0.15, 0.6};
  w.gravity = {0, 0, -9.81};
  test::fill_lattice(w, 3, w.lo, 2 * ny, ny, 2 * ny, dp);
  test::add_blocks(w);
  w.blocks->position[0] = {1.0, 0.075, 0.2};
  w.blocks->position[1] = {1.3, 0.075, 0.1};

  const std::string sync_json = sync ? "true" : "false";
  writers::Hdf5Writer h5(params_from_json(writers::Hdf5Writer::describe(), R"({"sync": )" + sync_json + "}"));
  writers::VtuWriter vtu(params_from_json(writers::VtuWriter::describe(), R"({"sync": )" + sync_json + "}"));
  writers::ProbesWriter probes(params_from_json(writers::ProbesWriter::describe(), R"({
      "points": [[0.1, 0.075, 0.05], [0.2, 0.075, 0.15]], "fields": ["pressure", "velocity_mag"],
      "gauges": [[0.1, 0.075, 0.0], [0.4, 0.075, 0.0]],
      "integrals": ["mass", "kinetic_energy", "potential_energy", "particles", "max_speed"]})"));
  const OutputContext context{out, "sample", "{\"talus\": 1, \"description\": \"writers_sample\"}", "0.1.0", false};
  h5.open(context, w);
  vtu.open(context, w);
  probes.open(context, w);

  using clock = std::chrono::steady_clock;
  double t_h5 = 0, t_vtu = 0, t_probes = 0;
  for (int f = 0; f < frames; ++f) {
    advance(w, f);
    auto t0 = clock::now();
    h5.write(w);
    auto t1 = clock::now();
    vtu.write(w);
    auto t2 = clock::now();
    probes.write(w);
    auto t3 = clock::now();
    t_h5 += std::chrono::duration<double>(t1 - t0).count();
    t_vtu += std::chrono::duration<double>(t2 - t1).count();
    t_probes += std::chrono::duration<double>(t3 - t2).count();
  }
  h5.close(w);
  vtu.close(w);
  probes.close(w);

  auto size_mb = [](const std::string& p) { return std::filesystem::file_size(p) / 1048576.0; };
  std::printf("particles %zu, frames %d, sync %s\n", w.fluid.size(), frames, sync ? "on" : "off");
  std::printf("hdf5   %8.1f ms/frame  %s %.2f MB\n", 1e3 * t_h5 / frames, (out + "/sample.h5part").c_str(),
              size_mb(out + "/sample.h5part"));
  std::printf("vtu    %8.1f ms/frame  %s %.2f MB per frame\n", 1e3 * t_vtu / frames,
              (out + "/sample_000000.vtu").c_str(), size_mb(out + "/sample_000000.vtu"));
  std::printf("probes %8.2f ms/frame  %s\n", 1e3 * t_probes / frames, (out + "/sample_probes.csv").c_str());
  return 0;
}
