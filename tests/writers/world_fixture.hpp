// Hand-built Worlds for the writer tests (no host): a lattice of fluid
// particles with the fields the host creates, a Wendland C2 kernel table, and
// optionally wall particles and blocks. Also a fresh temporary folder.
#pragma once

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <string>

#include "talus/blocks.hpp"
#include "talus/smoothing_kernel.hpp"
#include "talus/world.hpp"
#include "talus/writer.hpp"

namespace talus::test {

// Wendland C2 with support 2h (Wendland 1995): f(q) = (1 - q/2)^4 (2q + 1).
class TestWendlandC2 final : public SmoothingKernel {
 public:
  double support() const override { return 2.0; }
  double value_shape(double q) const override { return q < 2.0 ? std::pow(1.0 - 0.5 * q, 4) * (2.0 * q + 1.0) : 0.0; }
  double value_norm(int dim) const override { return dim == 2 ? 7.0 / (4.0 * M_PI) : 21.0 / (16.0 * M_PI); }
  double gradient_shape(double q) const override { return q < 2.0 ? -5.0 * q * std::pow(1.0 - 0.5 * q, 3) : 0.0; }
  double gradient_norm(int dim) const override { return value_norm(dim); }
};

inline void require_host_fields(ParticleStore& s) {
  // In float where the store is in mixed precision, as the host keeps them for a wcsph fluid.
  s.require({"velocity", FieldType::vector, "m/s", true, true, true});
  s.require({"density", FieldType::scalar, "kg/m^3", true, true, true});
  s.require({"pressure", FieldType::scalar, "Pa", true, true, true});
  s.require({"mass", FieldType::scalar, "kg", true, true, true});
}

// A dim-D lattice of nx * ny (* nz) particles at (i + 1/2) dp from `lo`,
// density rho0, mass rho0 dp^dim, h = 1.3 dp.
inline void fill_lattice(World& w, int dim, Vec3 lo, int nx, int ny, int nz, double dp, double rho0 = 1000.0) {
  w.dim = dim;
  w.dp = dp;
  w.h = 1.3 * dp;
  w.kernel = KernelTable(TestWendlandC2{}, dim, w.h);
  require_host_fields(w.fluid);
  if (dim == 2) nz = 1;
  const std::size_t n = static_cast<std::size_t>(nx) * ny * nz;
  const std::size_t first = w.fluid.append(n);
  auto pos = w.fluid.position();
  std::size_t i = first;
  for (int c = 0; c < nz; ++c)
    for (int b = 0; b < ny; ++b)
      for (int a = 0; a < nx; ++a, ++i)
        pos[i] = lo + Vec3{(a + 0.5) * dp, (b + 0.5) * dp, dim == 3 ? (c + 0.5) * dp : 0.0};
  w.fluid.visit_scalar("density", [&](auto rho) { std::fill(rho.begin() + first, rho.end(), rho0); });
  w.fluid.visit_scalar("mass", [&](auto m) { std::fill(m.begin() + first, m.end(), rho0 * std::pow(dp, dim)); });
}

inline OutputContext context_for(const std::string& dir, bool resume = false) {
  return OutputContext{dir, "scene", "{\"talus\": 1, \"description\": \"writer test\"}", "0.1.0-test", resume};
}

// Two small blocks (unit cubes scaled) for the block-state output.
inline void add_blocks(World& w) {
  w.blocks = std::make_unique<BlockSet>();
  auto& b = *w.blocks;
  for (int k = 0; k < 2; ++k) {
    b.name.push_back(k == 0 ? "rock" : "bed");
    b.body.push_back(k);
    b.fixed.push_back(k == 1);
    b.mass.push_back(2500.0 * (k + 1));
    b.inertia.push_back({1.0, 0, 0, 0, 2.0, 0, 0, 0, 3.0});
    Polyhedron p;
    const double s = 0.05 * (k + 1);
    for (int v = 0; v < 8; ++v) p.vertices.push_back({(v & 1 ? s : -s), (v & 2 ? s : -s), (v & 4 ? s : -s)});
    p.faces = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    b.shape.push_back(p);
    b.position.push_back({0.1 * k, 0.2, 0.3});
    b.orientation.push_back({std::cos(0.1 * k), 0.0, std::sin(0.1 * k), 0.0});
    b.velocity.push_back({1.0 + k, 0.0, -0.5});
    b.angular_velocity.push_back({0.0, 0.25 * k, 0.0});
    b.external_force.push_back({10.0 * k, 0.0, -3.0});
    b.external_torque.push_back({0.0, 0.0, 0.5 * k});
  }
}

// A fresh folder under the test binary's folder, removed on destruction.
class TempDir {
 public:
  explicit TempDir(const std::string& name) {
    path_ = std::filesystem::temp_directory_path() / ("talus-writers-" + name + "-" + std::to_string(::getpid()));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::permissions(path_, std::filesystem::perms::owner_all, ec);
    std::filesystem::remove_all(path_, ec);
  }
  std::string str() const { return path_.string(); }
  std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  std::filesystem::path path_;
};

}  // namespace talus::test
