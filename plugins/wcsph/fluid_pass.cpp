// The fluid-fluid passes of the wcsph stage: the fused force/continuity pass
// (one neighbour traversal, each pair once for both particles: mutual_pass.hpp)
// and the summation-density pass, and the order of
// all passes of one rate evaluation. The scene's choices are resolved here,
// once per evaluation, into one template instantiation; nothing in the pair
// loop branches on them.
#include <cmath>
#include <span>
#include <type_traits>

#include "fluid_fields.hpp"
#include "fluid_sums.hpp"
#include "talus/eos.hpp"
#include "talus/sph/fluid_terms.hpp"
#include "talus/sph/mutual_pass.hpp"
#include "talus/sph/pair_loop.hpp"
#include "talus/world.hpp"
#include "viscosity_term.hpp"
#include "wcsph_stage.hpp"

namespace talus::wcsph {

namespace {

// NB: sph::NeighbourFields<Real>, or UniformNeighbourFields<Real> for a fluid
// of one material and one mass.
template <class Real, class NB>
struct PassContext {
  World& world;
  const FluidFieldsOf<Real>& f;
  const NeighbourGrid& cells;
  const double* mu;  // per material
  Vec3 gravity;
  NB nb;  // the fluid's fields, with 1/rho
};

template <class Real, class NB, class... Terms>
sph::MutualPassResult run_force_pass(const PassContext<Real, NB>& ctx, const Terms&... terms) {
  const FluidFieldsOf<Real>& f = ctx.f;
  const double* mu = ctx.mu;
  const Vec3 g = ctx.gravity;
  auto start = [&](Index i) {
    FluidSums s;
    s.v = f.v[i];
    s.m = f.m[i];
    s.rho = f.rho[i];
    s.inv_rho = reciprocal(f.rho[i]);
    s.p = f.p[i];
    s.c = f.c[i];
    s.mu = mu ? mu[f.mat[i]] : ctx.nb.viscosity[i];
    s.kh = s.rho / (s.c * s.c);
    s.mat = f.mat[i];
    return s;
  };
  auto finish = [&](Index i) { f.a[i] = Vec3(f.a[i]) + g; };
  const sph::FluidReactions out{f.a.data(), f.drho.data()};
  return sph::mutual_pair_pass(ctx.cells, ctx.world.kernel, out, ctx.world.fluid.owned_size(), start, finish,
                               terms...);
}

template <class Real, class NB, class... Terms>
sph::MutualPassResult with_density_terms(const PassContext<Real, NB>& ctx, DensityMode density, Diffusion diffusion,
                                         double delta_h_c0, const Terms&... terms) {
  const NB nb = ctx.nb;
  if (density == DensityMode::summation) return run_force_pass(ctx, terms...);
  const sph::Continuity cont{nb};
  switch (diffusion) {
    case Diffusion::none: return run_force_pass(ctx, terms..., cont);
    case Diffusion::molteni:
      return run_force_pass(ctx, terms..., cont, sph::DensityDiffusion<false, NB>{nb, delta_h_c0, ctx.gravity});
    case Diffusion::fourtakas:
      return run_force_pass(ctx, terms..., cont, sph::DensityDiffusion<true, NB>{nb, delta_h_c0, ctx.gravity});
  }
  return {};
}

// Whether every row of the fluid (its halo too) has the mass and the material
// of the first.
template <class Real>
bool one_mass_and_material(const FluidFieldsOf<Real>& f) {
  const std::size_t n = f.m.size();
  if (n == 0) return false;
  const Real m0 = f.m[0];
  const std::int32_t mat0 = f.mat[0];
  std::size_t other = 0;
#pragma omp parallel for schedule(static) reduction(+ : other) if (n >= sph::parallel_min)
  for (std::size_t i = 0; i < n; ++i) other += (f.m[i] != m0) | (f.mat[i] != mat0);
  return other == 0;
}

// The fluid's fields side by side, for the mutual pass to gather, in the
// scratch (what it held is gone).
template <class Real>
const sph::NeighbourRecordOf<Real>* fill_records(const FluidFieldsOf<Real>& f, SharedScratch& scratch) {
  const std::size_t n = f.rho.size();
  // The spare record the gather's last load may read into.
  const std::span<sph::NeighbourRecordOf<Real>> r = scratch.hold<sph::NeighbourRecordOf<Real>>(n + 1);
  r[n] = {};
#pragma omp parallel for schedule(static) if (n >= sph::parallel_min)
  for (std::size_t i = 0; i < n; ++i) {
    if constexpr (std::is_same_v<Real, float>)
      r[i] = {f.v[i].x, f.v[i].y, f.v[i].z, f.rho[i], f.p[i], f.c[i]};
    else
      r[i] = {f.rho[i], f.p[i], f.c[i], reciprocal(f.rho[i])};
  }
  return r.data();
}

}  // namespace

// Per-particle reciprocals once per evaluation instead of divisions per pair.
void WcsphStage::refresh_reciprocals(World& world) {
  with_fluid_fields(world.fluid, [&](auto f) {
    const std::size_t n = f.rho.size();
    using Real = typename decltype(f.rho)::value_type;
    const std::span<Real> inv_rho = fluid_scratch_.hold<Real>(n);
#pragma omp parallel for schedule(static) if (n >= 4096)
    for (std::size_t i = 0; i < n; ++i) inv_rho[i] = reciprocal(f.rho[i]);
  });
}

// The three-pass viscosity reads mu_eff per particle: the general fields.
bool WcsphStage::fluid_pass_gathers_records(World& world) const {
  return !per_particle_viscosity_ && with_fluid_fields(world.fluid, [](auto f) { return one_mass_and_material(f); });
}

std::uint64_t WcsphStage::fluid_pass(World& world, bool gather_records) {
  const sph::MutualPassResult result = with_fluid_fields(world.fluid, [&](auto f) {
    using Real = typename decltype(f.rho)::value_type;
    auto nb = f.neighbours();
    // The three-pass viscosity's force pass reads mu_eff of both particles; start() then takes mu_eff[i].
    if (per_particle_viscosity_) nb.viscosity = world.fluid.scalar("mu_eff").data();
    const double delta_h_c0 = delta_ * h_ * c0_max_;
    sph::MutualPassResult passed;
    auto run = [&](const auto& fields) {
      const PassContext<Real, std::decay_t<decltype(fields)>> ctx{
          world, f, cells_, per_particle_viscosity_ ? nullptr : material_mu_.data(), world.gravity, fields};
      const sph::PressureForce pressure{fields};
      with_viscosity_term<Neighbour::fluid>(viscosity_settings(world), fields, fields, [&](const auto& viscous) {
        passed = with_density_terms(ctx, density_, diffusion_, delta_h_c0, pressure, viscous);
        return passed.evaluations;
      });
    };
    if (gather_records) {
      sph::UniformNeighbourFields<Real> uniform{nb};
      uniform.mass_of_all = f.m[0];
      uniform.material_of_all = f.mat[0];
      sph::GatheredNeighbourFields<Real> gathered{uniform};
      gathered.record = fill_records(f, fluid_scratch_);
      run(gathered);
    } else {
      nb.inv_density = reciprocals<Real>().data();
      run(nb);
    }
    return passed;
  });
  fluid_visc_max_ = result.visc_max;
  return result.evaluations;
}

void WcsphStage::density_summation(World& world) {
  with_fluid_fields(world.fluid, [&](auto f) {
    struct Sums {
      double rho_sum = 0.0;
    };
    const double w0 = world.kernel.w0();
    const auto m = f.m;
    auto start = [](Index) { return Sums{}; };
    auto finish = [&](Index i, const Sums& s) { f.rho[i] = s.rho_sum + m[i] * w0; };  // self term W(0)
    // Owned rows only: the halo's densities come from their owners after the pass.
    const std::span<const Vec3> x = f.x;
    pairs_total_ += sph::pair_pass(world.fluid.owned_size(), x, cells_, world.kernel, sph::same_set, start, finish,
                                   sph::DensitySum{m.data()});
  });
  pairs_total_ += wall_density_passes(world);
}

// On several MPI ranks the halo rows were moved by their own, partial rates:
// every field comes from the owners before an evaluation reads it.
void WcsphStage::refresh_halos(World& world) {
  Parallel& ranks = world.parallel();
  if (ranks.ranks() == 1) return;
  for (ParticleStore* store : {&world.fluid, &world.boundary}) {
    halo_fields_.clear();
    for (const FieldInfo& field : store->fields()) halo_fields_.push_back(field.name);
    ranks.refresh_halo(*store, halo_fields_);
  }
}

void WcsphStage::update_pressure(World& world) {
  with_fluid_fields(world.fluid, [&](auto f) {
    for (int m : fluid_materials_)
      pressure_of(*world.materials[m].eos, world.material_particles(m), f.rho.data(), f.p.data(), f.c.data());
  });
}

void WcsphStage::compute_rates(World& world) {
  keep_fluid_fields_alike(world.fluid);  // a later stage's setup may have widened one
  refresh_halos(world);
  cells_.build(world.fluid.position());
  if (density_ == DensityMode::summation) {
    density_summation(world);
    static const std::string density[] = {"density"};
    world.parallel().refresh_halo(world.fluid, density);
    update_pressure(world);
  }
  // 1/rho and the records take turns in one scratch: the fused pass forms
  // j's 1/rho from its record, and every other pass reads the column.
  const bool gather_records = fluid_pass_gathers_records(world);
  if (!gather_records) refresh_reciprocals(world);
  if (per_particle_viscosity_) {
    pairs_total_ += strain_rate_pass(world);
    apparent_viscosity_pass(world);
  }
  pairs_total_ += fluid_pass(world, gather_records);
  if (gather_records) refresh_reciprocals(world);
  rates_visc_max_ = 0.0;
  pairs_total_ += wall_passes(world);
  if (!pair_terms_.empty()) {
    const sph::FluidView view = fluid_view(world);
    const sph::FluidRates rates = fluid_rates(world);
    for (sph::PairTerm* term : pair_terms_) pairs_total_ += term->add_rates({world, view, rates});
  }
  if (point_implicit_) scale_stiff_particles(world);
  ++rate_evaluations_;
  rates_valid_ = true;
  rates_step_ = world.step;
  rates_time_ = world.time;
  rates_size_ = world.fluid.size();
}

}  // namespace talus::wcsph
