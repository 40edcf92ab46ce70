// Depth-integrated SPH run-out over terrain (seed pfe-ie §2.2, eqs 8-9 and
// 19-28; Pastor et al. 2009). Particles live in plan view (x, y) over the
// terrain Z(x, y) and carry a fixed volume V_i (their mass is rho V_i, so
// mass is conserved exactly) and the plan part v of their velocity along the
// surface, u = (v, grad Z . v), speed |u|.
//
// Equations of motion. For a particle held on z = Z(x, y) by the normal
// reaction N n (n the unit normal), the plan coordinates have the metric
// M = I + grad Z grad Z^T (kinetic energy 1/2 v^T M v), and Lagrange's
// equations give
//   dv/dt = M^-1 a_p - cos^2(theta) grad Z (g + v.H.v),   H = Hessian of Z,
//   N / m  = cos(theta) (g + v.H.v)                       (the normal load g_n),
// with cos^2(theta) = 1 / (1 + |grad Z|^2) and a_p the pressure force in plan.
// The v.H.v terms are the centripetal part: without them a flow that turns
// from a slope onto a floor loses the kinetic energy of its normal component
// (cos^2 of the angle turned). They enter as follows:
//   - in the motion, through follow_surface(): after each drift the surface
//     velocity is projected onto the tangent plane at the new point and keeps
//     its magnitude (to first order in dt exactly the term above; at a sharp
//     break the redirection the break imposes, with no loss);
//   - in the basal law, through g_n = cos (g + v.H.v) with H from the terrain
//     (analytic, or the DEM's smoothed bicubic surface; terrain.hpp), for every
//     rheology, built-in or third-party, that uses the normal load. Over convex
//     terrain fast enough that g_n < 0 the flow would take off: g_n is clamped
//     at 0 (no friction), the flow keeps following the surface, and the
//     particle-steps are counted in the status line and the summary.
//   The earth pressure keeps g cos(theta) (its own centrifugal correction is
//   O(h / R), left out as in the seed), but its energy, 1/2 g cos^2 sigma per
//   unit volume, varies with the slope under a particle: the force of that,
//   g sigma cos^4 H grad Z, is part of a_p, so the scheme is the Lagrangian
//   one of kinetic + potential + hydrostatic energy and keeps that total.
//
//   depth     sigma_i = sum_j V_j W(x_i - x_j, l_i)            (eq. 25-26, vertical)
//             h_i = sigma_i cos(theta_i)                       (slope-normal depth)
//   pressure  p = 1/2 g cos(theta) h^2 (eq. 28, b3 = -g cos theta); with
//             p / sigma^2 = 1/2 g c^2 the symmetric SPH gradient is
//             a_p = -sum_j V_j 1/4 g (c_i^2 + c_j^2) (gradW_ij(l_i) / alpha_i +
//             gradW_ij(l_j) / alpha_j) (alpha: grad-h factor), mapped from the
//             plan to the surface with M^-1;
//   gravity   the plan components of g projected on the tangent plane,
//             -g cos^2(theta) grad Z;
//   friction  tau_b from the material's Rheology::basal_shear (one batch
//             call per material, normal load g_n above), applied implicitly
//             after the first kick: it only slows a particle and stops it
//             within the step, and holds it while it can absorb the step's kick.
//   viscosity Monaghan's artificial viscosity between approaching particles,
//             alpha (artificial_viscosity) with the wave speed sqrt(g h):
//             damps particle noise; a flow moving as a whole does not feel it.
//   smoothing l_i = (h_over_dp) sqrt(V_i / sigma_i) (flow spreading in plan) or
//             l_0 sigma_0 / sigma_i (spreading along one direction), within
//             bounds; updated from the depth at the step's positions before
//             the pressure force, which so never uses a smoothing length a
//             step behind the particles.
//   time      pressure kick, gravity kick-drift-kick (second order along curved
//             terrain), the drift scaled to cover dt |u| of surface,
//             dt = cfl l / (sqrt(g h) + |v|).
//   neighbours talus::NeighbourGrid with per-particle radii: particles binned
//             by smoothing length, so the few large-l particles of a thin
//             front do not set every cell's size.
// On an inclined plane this reduces exactly to the Savage-Hutter equations
// in slope coordinates that Mangeney et al. (2000) solve.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "talus/neighbour_grid.hpp"
#include "talus/rheology.hpp"
#include "talus/stage.hpp"
#include "rasters.hpp"
#include "terrain.hpp"
#include "variable_kernel.hpp"

namespace talus::runout {

class DepthIntegratedSph final : public Stage {
 public:
  static ParamSet describe();
  explicit DepthIntegratedSph(const ParamValues& v);

  StageParts parts(const World&) const override { return {{}, {}, {"velocity"}}; }  // the bodies' start velocity
  void setup(World& world) override;
  double stable_time_step(World& world) override;
  void advance(World& world, double dt) override;
  StagePlan plan(const World& world) const override;
  std::string why_not_on_ranks() const override {
    return "the depth-integrated run-out keeps its particles' neighbours and its rasters on one process";
  }
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
  // Particle-steps in which the centrifugal term over convex terrain cancelled
  // the normal load (the flow would lift off; it follows the surface without friction).
  std::uint64_t lifted_particle_steps() const { return lifted_steps_; }

 private:
  void compute_depth(World& world, int iterations);
  void sum_depth(World& world);
  void update_smoothing(std::span<const double> volume, std::span<double> smoothing) const;
  void bin_particles(std::span<const Vec3> pos, std::span<const double> smoothing);
  void record(World& world);
  void remove_off_terrain(World& world);

  ParamValues params_;
  std::unique_ptr<Terrain> terrain_;
  VariableKernel kernel_;
  NeighbourGrid grid_;  // binned by smoothing length
  RunoutRasters rasters_;
  double g_ = 9.81, cfl_ = 0.2, kappa_ = 1.3, l_min_ = 0.0, l_max_ = 0.0, threshold_ = 0.01;
  double max_accel_ = 0.0, runout_ = 0.0;
  std::uint64_t lifted_steps_ = 0, lifted_now_ = 0;  // particle-steps with no basal contact (convex take-off)
  std::uint64_t off_terrain_ = 0;                     // particles removed over undefined terrain
  double dp_ = 1.0;
  bool variable_smoothing_ = true, depth_law_ = false;
  std::int64_t raster_every_ = 1;
  double viscosity_ = 0.0;  // Monaghan alpha
  std::string raster_prefix_;
  Vec3 crown_{};
  std::vector<int> materials_;  // materials with particles, checked at setup
  std::vector<std::string> notes_;

  // Scratch, re-filled every step (sized when the particle count changes).
  std::vector<double> reach_, z_, cos_, sigma_, alpha_, speed_, density_, gn_, tau_, hold_, whole_speed_, wave_;
  double alpha_floor_ = 0.2;  // bounds the grad-h factor of nearly isolated particles
  std::vector<Vec3> grad_, next_grad_, accel_, trial_;
  std::vector<Hessian> hess_;
};

}  // namespace talus::runout
