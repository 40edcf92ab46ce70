// Dynamic boundary particles (DBC; Crespo, Gómez-Gesteira & Dalrymple 2007,
// CMC 5(3); as DualSPHysics implements them, Domínguez et al. 2022).
// Layers of wall particles carry a density from the continuity equation with
// their fluid neighbours,
//   drho_b/dt = sum_f m_f (v_b - v_f) . grad W_bf,
// never below the reference density (as DualSPHysics, so that walls never pull
// fluid in), a pressure from the EOS of the wall's reference material, and push
// on the fluid with the same symmetric pressure and viscous terms as fluid
// neighbours. Wall particles follow the body's prescribed "motion" if any.
// Initial wall density: the hydrostatic extrapolation of the neighbouring fluid
// pressure (Adami et al. 2012, J. Comput. Phys. 231, eq. 27) so that a column
// started hydrostatic is held from the first step.
#pragma once

#include <vector>

#include "talus/sph/neighbour_grid.hpp"
#include "talus/motion.hpp"
#include "talus/sph/boundary_pass.hpp"

namespace talus::boundary {

class DynamicParticles final : public sph::SphBoundary {
 public:
  static ParamSet describe();
  explicit DynamicParticles(const ParamValues&) {}

  void setup(World& world, std::span<const int> bodies) override;
  void bind(World& world, const sph::FluidSettings& settings) override;
  void begin_step(World& world) override;
  void interact(World& world, const sph::FluidView& fluid, const sph::FluidRates& rates) override;
  void add_density(const World& world, const sph::FluidView& fluid, std::span<double> rho) override;
  void advance_walls(World& world, double time, double dt) override;
  std::uint64_t pair_count() const override { return pairs_; }
  void describe_passes(StagePlan& plan) const override;

  std::size_t first() const { return first_; }
  std::size_t count() const { return count_; }

 private:
  void update_pressure(World& world);
  void initial_density(World& world);

  std::vector<int> bodies_;
  std::vector<std::string> body_names_;
  std::size_t first_ = 0, count_ = 0;         // my particles in world.boundary
  std::vector<std::vector<Index>> by_material_;  // wall indices per material, for the EOS calls
  std::vector<double> rho0_of_material_;
  std::vector<PrescribedMotion> motion_;       // per body slot
  std::vector<int> slot_of_body_;              // world body index -> slot (-1: not mine)
  bool moves_ = false;
  sph::FluidSettings settings_;
  sph::NeighbourGrid cells_;
  std::vector<double> inv_rho_;  // 1/rho of my wall particles, refreshed with their pressure
  std::uint64_t pairs_ = 0;
};

}  // namespace talus::boundary
