// Dynamic boundary particles (DBC; Crespo, Gómez-Gesteira & Dalrymple 2007,
// CMC 5(3); as DualSPHysics implements them, Domínguez et al. 2022).
// Layers of wall particles carry a density from the continuity equation with
// their fluid neighbours,
//   drho_b/dt = sum_f m_f (v_b - v_f) . grad W_bf,
// never below the reference density (as DualSPHysics, so that walls never pull
// fluid in), a pressure from the EOS of the wall's reference material, and push
// on the fluid with the same symmetric pressure and viscous terms as fluid
// neighbours (the stage's fluid-wall pass over this model's wall set). Wall
// particles follow the body's prescribed "motion" if any.
// Initial wall density: the hydrostatic extrapolation of the neighbouring fluid
// pressure (Adami et al. 2012, J. Comput. Phys. 231, eq. 27) so that a column
// started hydrostatic is held from the first step.
//
// No-slip in the laminar (and Laplacian) viscous term, parameter "no_slip":
//   extrapolated (default): the wall particle enters the fluid-wall viscous
//     term with the mirrored velocity v_b* = 2 v_b - v~_b, v~_b the Shepard
//     interpolation of the fluid velocity at b, v~_b = sum_f v_f W_bf / sum_f W_bf
//     (Adami, Hu & Adams 2012, J. Comput. Phys. 231, eqs. 22-23; the idea of
//     Morris, Fox & Zhu 1997, J. Comput. Phys. 136, sec. 3.3). The velocity
//     then vanishes (relative to the wall) on the wall surface, half a spacing
//     in front of the first wall layer, not on the wall particles themselves:
//     a plane Poiseuille profile converges at second order instead of first.
//   wall_velocity: the wall particle's own (prescribed) velocity, as
//     DualSPHysics' DBC does; the no-slip plane then lies ~0.7 dp behind the
//     wall surface (first-order error in dp).
// Pressure and continuity always use the wall's own velocity, and the
// artificial viscosity (not a no-slip model) too: scenes with
// "viscosity": "artificial" are unchanged by this option.
#pragma once

#include <vector>

#include "talus/neighbour_grid.hpp"
#include "talus/motion.hpp"
#include "talus/sph/boundary_pass.hpp"

namespace talus::boundary {

class DynamicParticles final : public sph::SphBoundary {
 public:
  static ParamSet describe();
  enum class NoSlip { extrapolated, wall_velocity };
  explicit DynamicParticles(const ParamValues& v);

  void setup(World& world, std::span<const int> bodies) override;
  void bind(World& world, const sph::FluidSettings& settings) override;
  void begin_step(World& world) override;
  std::uint64_t fill_wall_state(World& world, const sph::FluidView& fluid) override;
  void refresh_wall_sets(World& world) override;
  std::span<const sph::WallSet> wall_sets() const override {
    return count_ > 0 ? std::span<const sph::WallSet>(&set_, 1) : std::span<const sph::WallSet>();
  }
  void advance_walls(World& world, double time, double dt) override;
  void describe_passes(StagePlan& plan) const override;

  std::size_t first() const { return first_; }
  std::size_t count() const { return count_; }

 private:
  void update_pressure(World& world);
  void initial_density(World& world);
  void refresh_set(World& world);  // set_ at the store's current arrays

  std::vector<int> bodies_;
  std::vector<std::string> body_names_;
  std::size_t first_ = 0, count_ = 0;         // my particles in world.boundary
  std::vector<std::vector<Index>> by_material_;  // wall indices per material, for the EOS calls
  std::vector<double> rho0_of_material_;
  std::vector<PrescribedMotion> motion_;       // per body slot
  std::vector<int> slot_of_body_;              // world body index -> slot (-1: not mine)
  bool moves_ = false;
  sph::FluidSettings settings_;
  NeighbourGrid cells_;
  std::vector<double> inv_rho_;  // 1/rho of my wall particles, refreshed by every fill_wall_state()
  NoSlip no_slip_ = NoSlip::extrapolated;
  bool mirror_ = false;           // no_slip extrapolated and a viscous term that uses it (laminar, Laplacian)
  std::vector<Vec3> noslip_v_;    // v_b* of my wall particles, refilled by every fill_wall_state()
  sph::WallSet set_;              // all my wall particles, one set
};

}  // namespace talus::boundary
