// Depth-integrated SPH run-out over terrain (seed pfe-ie §2.2, eqs 8-9 and
// 19-28; Pastor et al. 2009). Particles live in plan view (x, y) over the
// terrain Z(x, y) and carry a fixed volume V_i (their mass is rho V_i, so
// mass is conserved exactly) and a depth-averaged velocity.
//
//   depth     sigma_i = sum_j V_j W(x_i - x_j, l_i)            (eq. 25-26, vertical)
//             h_i = sigma_i cos(theta_i)                       (slope-normal depth)
//   pressure  p = 1/2 g cos(theta) h^2 (eq. 28, b3 = -g cos theta); with
//             p / sigma^2 = 1/2 g c^2 the symmetric SPH gradient is
//             a_p = -sum_j V_j 1/4 g (c_i^2 + c_j^2) (gradW_ij(l_i) / alpha_i +
//             gradW_ij(l_j) / alpha_j) (alpha: grad-h factor), mapped from the
//             plan to the surface with the inverse metric (I + gZ gZ^T)^-1;
//   gravity   the plan components of g projected on the tangent plane,
//             -g cos^2(theta) grad Z;
//   friction  tau_b from the material's Rheology::basal_shear (one batch
//             call per material), applied implicitly after the driving
//             forces: it only slows a particle and stops it within the step.
//   smoothing l_i = (h_over_dp) sqrt(V_i / sigma_i) (flow spreading in plan) or
//             l_0 sigma_0 / sigma_i (spreading along one direction), within bounds.
//   time      symplectic Euler (kick then drift), dt = cfl l / (sqrt(g h) + |v|).
//   neighbours LevelGrid: particles binned by smoothing length, so the few
//             large-l particles of a thin front do not set every cell's size.
// On an inclined plane this reduces exactly to the Savage-Hutter equations
// in slope coordinates that Mangeney et al. (2000) solve.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "talus/rheology.hpp"
#include "talus/stage.hpp"
#include "level_grid.hpp"
#include "rasters.hpp"
#include "terrain.hpp"
#include "variable_kernel.hpp"

namespace talus::runout {

class DepthIntegratedSph final : public Stage {
 public:
  static ParamSet describe();
  explicit DepthIntegratedSph(const ParamValues& v);

  void setup(World& world) override;
  double stable_time_step(const World& world) override;
  void advance(World& world, double dt) override;
  StagePlan plan(const World& world) const override;
  std::string status(const World& world) const override;

  // Writes the rasters (PREFIX_*.asc); the stage does it by itself at
  // end_time when `rasters` is set. Returns the files written.
  std::vector<std::string> finish(World& world, const std::string& output_directory) override;
  std::vector<std::string> write_rasters(const std::string& prefix) const;

  const Terrain& terrain() const { return *terrain_; }
  const RunoutRasters& rasters() const { return rasters_; }
  double runout_distance() const { return runout_; }
  double total_volume(const World& world) const;
  double gravity() const { return g_; }

 private:
  void compute_depth(World& world, int iterations);
  void update_smoothing(std::span<const double> volume, std::span<double> smoothing) const;
  void bin_particles(std::span<const Vec3> pos, std::span<const double> smoothing);
  void record(World& world);

  ParamValues params_;
  std::unique_ptr<Terrain> terrain_;
  VariableKernel kernel_;
  LevelGrid grid_;  // neighbour search binned by smoothing length
  RunoutRasters rasters_;
  double g_ = 9.81, cfl_ = 0.2, kappa_ = 1.3, l_min_ = 0.0, l_max_ = 0.0, threshold_ = 0.01;
  double max_accel_ = 0.0, runout_ = 0.0;
  double dp_ = 1.0;
  bool variable_smoothing_ = true, depth_law_ = false;
  std::int64_t raster_every_ = 1;
  std::string raster_prefix_;
  Vec3 crown_{};
  std::vector<int> materials_;  // materials with particles, checked at setup
  std::vector<std::string> notes_;

  // Scratch, re-filled every step (sized when the particle count changes).
  std::vector<double> reach_, z_, cos_, sigma_, alpha_, speed_, density_, gn_, tau_;
  double alpha_floor_ = 0.2;  // bounds the grad-h factor of nearly isolated particles
  std::vector<Vec3> grad_, accel_;
};

}  // namespace talus::runout
