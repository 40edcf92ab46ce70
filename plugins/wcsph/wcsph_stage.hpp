// The `wcsph` stage: weakly compressible SPH for water in 2D and 3D.
//
// Equations (coastline seed §2.3 as DualSPHysics implements them, Domínguez
// et al. 2022, Comput. Part. Mech. 9; rock-fluid seed §3 for its options):
//   dv_i/dt   = -sum_j m_j (p_i + p_j)/(rho_i rho_j) grad W_ij + viscous + g
//   drho_i/dt =  sum_j m_j v_ij . grad W_ij + density diffusion      (continuity)
//   or rho_i  =  sum_j m_j W_ij                                      (summation, seed eq. 12)
//   p_i       =  EOS of i's material (one batch call per material per evaluation)
// viscous: Monaghan artificial viscosity (alpha), Morris/Lo-Shao laminar with the
// material's Newtonian viscosity, or the rock-fluid seed's Laplacian-kernel form
// (eq. 18, Müller kernel). Density diffusion: Molteni-Colagrossi 2009 or Fourtakas
// et al. 2019. Time step (coastline seed, CFL condition):
//   dt = C min( sqrt(h/|f|max), h/(c_max + h max|v_ij.x_ij|/(r^2+eta^2)), h^2/nu_max ).
// Integrators: symplectic (DualSPHysics, default), Verlet with a corrective
// step every N (DualSPHysics), predictor-corrector (Monaghan 1989; the seed's),
// explicit Euler (rock-fluid seed eqs. 20-21).
// Walls are separate passes over the wall sets of sph::SphBoundary models
// (boundary_pass.hpp); the scene's extra pair terms run after them (pair_term.hpp).
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "talus/neighbour_grid.hpp"
#include "talus/sph/boundary_pass.hpp"
#include "talus/sph/fluid_terms.hpp"
#include "talus/sph/mutual_pass.hpp"
#include "talus/sph/pair_term.hpp"
#include "talus/stage.hpp"
#include "shared_scratch.hpp"
#include "viscosity_term.hpp"

namespace talus::wcsph {

enum class Integrator { symplectic, verlet, predictor_corrector, euler };
enum class DensityMode { continuity, summation };
enum class Diffusion { none, molteni, fourtakas };

// sum_j V_j |x_ij . grad W_ij|/(r^2 + eta^2) over a full square/cubic lattice
// support at the fluid's spacing (viscosity_passes.cpp): the Morris operator's
// diagonal per unit viscosity/density where walls fill the support.
double lattice_viscous_support(const World& world);

class WcsphStage final : public Stage {
 public:
  static ParamSet describe();
  explicit WcsphStage(const ParamValues& v);

  void setup(World& world) override;
  // Blocks, when a block body has a boundary model (the fluid sees it).
  StageParts parts(const World& world) const override;
  double stable_time_step(World& world) override;
  void advance(World& world, double dt) override;
  StagePlan plan(const World& world) const override;
  // Every pass refreshes the halo fields it reads (refresh_halos) and loops over owned rows.
  std::string why_not_on_ranks() const override { return {}; }
  // "rho dev X% (worst Y% at t = T s)": the current max |rho/rho0 - 1| and its
  // running maximum over the run (the harness reads both from the summary).
  std::string status(const World& world) const override;
  // The Verlet step counter and the worst density deviation: the state outside the particle store.
  std::string save_state() const override;
  void load_state(std::string_view bytes) override;

  // For tests and benchmarks: evaluate the rates at the current state.
  void compute_rates(World& world);
  std::uint64_t pair_evaluations() const { return pairs_total_; }  // since setup
  std::uint64_t rate_evaluations() const { return rate_evaluations_; }
  double max_density_deviation(const World& world) const;
  // Running maximum of max_density_deviation() over the setup state and the end of every step.
  double worst_density_deviation() const { return worst_deviation_; }
  double worst_density_deviation_time() const { return worst_deviation_time_; }

 private:
  // Whether the fluid's fields may be kept in float (fluid_fields_in_float).
  bool single_fluid_allowed(const World& world) const;
  void update_pressure(World& world);
  void refresh_halos(World& world);
  // Three-pass non-Newtonian viscosity (DESIGN.md), only when per_particle_viscosity_:
  // pass 1 shear rate, pass 2 mu_eff (one rheology batch call per material, plus
  // the Smagorinsky eddy viscosity); pass 3 is the force pass reading mu_eff.
  std::uint64_t strain_rate_pass(World& world);
  void apparent_viscosity_pass(World& world);
  // stiff_viscosity point_implicit (viscosity_passes.cpp): divide each particle's
  // acceleration by its inertia factor 1 + dt D_i after all passes.
  void scale_stiff_particles(World& world);
  // 1/rho per fluid particle into the shared scratch, for the passes that
  // read it from a column (every pass but the fused one when it gathers records).
  void refresh_reciprocals(World& world);
  template <class Real>
  std::span<const Real> reciprocals() const {
    return fluid_scratch_.held<Real>();
  }
  // Whether the fused fluid pass reads j's fields from records: a fluid of one
  // mass and one material, without the three-pass viscosity.
  bool fluid_pass_gathers_records(World& world) const;
  std::uint64_t fluid_pass(World& world, bool gather_records);
  ViscositySettings viscosity_settings(const World& world) const;
  // The fluid-wall passes (wall_passes.cpp): every wall model's wall-side hook,
  // then the fluid against each of its wall sets, then its direct forces.
  std::uint64_t wall_passes(World& world);
  // Summation density: the wall sets' share sum_b m_b W_ib of rho_i.
  std::uint64_t wall_density_passes(World& world);
  // The fluid as the wall models and pair terms see it, for this evaluation.
  sph::FluidView fluid_view(World& world) const;
  // The fluid's rates as the wall models and pair terms add to them.
  sph::FluidRates fluid_rates(World& world);
  void density_summation(World& world);
  bool rates_current(const World& world) const;
  void step_euler(World& world, double dt);
  void step_verlet(World& world, double dt);
  void step_two_stage(World& world, double dt);  // symplectic and predictor-corrector

  // Parameters.
  Integrator integrator_;
  int verlet_steps_;
  double courant_;
  ViscosityModel viscosity_;
  double alpha_;
  DensityMode density_;
  Diffusion diffusion_;
  double delta_;
  bool smagorinsky_;
  double smagorinsky_cs_;
  sph::ViscosityMean viscosity_mean_;
  ParamValues params_;

  // Set up once.
  double h_ = 0.0, c0_max_ = 0.0, nu_max_ = 0.0;
  std::vector<double> material_mu_;    // Pa s, per material
  std::vector<double> material_rho0_;  // kg/m^3, per material
  std::vector<int> fluid_materials_;   // materials with fluid particles and an EOS
  std::vector<int> rheology_materials_;  // fluid materials whose mu_eff comes from a batch call (non-Newtonian)
  bool per_particle_viscosity_ = false;  // mu_eff field and the three passes in use
  double nu_field_max_ = 0.0;            // max mu_eff/rho of the last evaluation, 1/(m^2/s)
  bool point_implicit_ = false;          // stiff_viscosity: point_implicit
  double bulk_viscous_support_ = 0.0;    // sum_j V_j |x_ij.grad W|/(r^2+eta^2) of a full lattice support, 1/m^2
  std::vector<double> visc_support_, inertia_;  // scratch (point_implicit), refilled every evaluation (grow only)
  std::vector<sph::SphBoundary*> walls_;
  std::vector<sph::PairTerm*> pair_terms_;  // the scene's extra terms (sph/pair_term.hpp), in order
  sph::FluidSettings settings_;
  NeighbourGrid cells_;
  Vec3 period_;  // domain length on periodic axes (lever arms of rigid-body wall sets)
  SharedScratch fluid_scratch_;  // the fused pass's neighbour records, then 1/rho (shared_scratch.hpp)
  // The largest |v_ij.x_ij|/(r^2+eta^2), 1/s, of the fluid pass and of the
  // wall passes and pair terms (FluidRates::visc_max).
  double fluid_visc_max_ = 0.0, rates_visc_max_ = 0.0;
  std::vector<double> visc_max_by_thread_;  // the wall passes' maxima, a cache line per thread
  std::vector<std::string> halo_fields_;       // scratch: the fields refresh_halos() sends

  // Step state.
  std::uint64_t verlet_counter_ = 0;
  std::uint64_t pairs_total_ = 0, rate_evaluations_ = 0;
  double worst_deviation_ = 0.0, worst_deviation_time_ = 0.0;  // one O(N) reduction per step, no allocation
  bool rates_valid_ = false;
  std::uint64_t rates_step_ = 0;
  double rates_time_ = 0.0;
  std::size_t rates_size_ = 0;
};

}  // namespace talus::wcsph
