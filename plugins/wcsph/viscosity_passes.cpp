// Passes 1 and 2 of the three-pass non-Newtonian viscosity (DESIGN.md, "Non-
// Newtonian viscosity is three passes"); pass 3 is the force pass of
// fluid_pass.cpp with sph::LaminarViscosityField. None of this runs for a
// scene whose materials are all Newtonian without eddy viscosity.
//
// Eddy viscosity: the Smagorinsky model in the SPS form of Dalrymple & Rogers
// (2006, Coast. Eng. 53) as DualSPHysics uses it (the coastline seed's
// mu = mu_d + mu_t, §2.3.2): mu_t = rho (Cs dp)^2 |S|, |S| = sqrt(2 S:S), the
// filter width the particle spacing.
//
// stiff_viscosity point_implicit: with the explicit viscous term a particle
// whose viscous relaxation time 1/D_i (D_i = sum_j of its Morris coefficients
// m_j mu_ij/(rho_i rho_j) |x_ij.grad W|/(r^2+eta^2)) is shorter than the step
// needs dt < 2/D_i: the C h^2 rho/mu bound, ~1e-6 s for an unyielded sediment
// at its plug viscosity. Backward Euler for the viscous term of particle i
// alone (neighbours' velocities lagged, one Jacobi sweep) gives
//   v_i' = v_i + dt a_i / (1 + dt D_i),  a_i = pressure + viscous + gravity,
// i.e. the particle's inertia multiplied by 1 + dt D_i (a local mass scaling).
// The update of v_i is then a convex combination of v_i and its neighbours'
// velocities for the viscous part: stable for any D_i (the eigenvalues of the
// scaled operator stay below 2 D_i/(1 + dt D_i) < 2/dt, inside the two-stage
// integrator's region), and a state with a_i = 0 is unchanged, so the
// equilibria and the quasi-static (Stokes-regime) velocities, where the
// viscous force balances the others, are those of the explicit scheme. Only
// particles with dt D_i >~ 1 feel it: a plug/unyielded region (whose own
// relaxation is faster than one step anyway); a water particle has dt D_i ~ 1e-5.
// The price: the transient of a stiff region is slowed, most for rigid motion
// (no viscous force, inertia still 1 + dt D_i): a plug that must accelerate as
// a whole (the Bingham channel's, spun up from rest by a body force) takes ~dt D
// times longer to reach its steady speed. Meant for plugs that should stay at
// rest (the sediment bank's core); the flanks' collapse, once yielded (dt D < 1),
// is little changed (sediment_bank_2d: flank displacement 13 % behind at 0.1 s,
// within 3 % at 2 s).
// D_i is bounded without the neighbours' mu_eff: the harmonic pair viscosity
// 4 mu_i mu_j/(mu_i + mu_j) <= 4 mu_i, and where walls fill the support (whose
// no-slip mirror velocity ~ -v_i doubles their share) the full lattice sum
// stands for fluid + wall: D_i <= 4 mu_i max(S_i, S_lattice)/rho_i with
// S = sum_j V_j |x_ij.grad W|/(r^2+eta^2). dt is bounded by the acoustic step
// C h / c0 (the actual step is never larger), which only overestimates 1 + dt D_i.
#include <algorithm>
#include <cmath>

#include "fluid_fields.hpp"
#include "talus/rheology.hpp"
#include "talus/sph/fluid_terms.hpp"
#include "talus/sph/pair_loop.hpp"
#include "talus/world.hpp"
#include "wcsph_stage.hpp"

namespace talus::wcsph {

namespace {
struct StrainSums {
  Vec3 v;
  double g[3][3] = {};
  double l[3][3] = {};
  double support = 0.0;  // sum_j V_j |x_ij.grad W|/(r^2+eta^2) (point_implicit only)
};

// S_i of the point-implicit viscous inertia, summed in the strain-rate pass.
struct ViscousSupport {
  static constexpr bool uses_value = false, uses_gradient = true;
  sph::Neighbours nb;
  double eta2 = 0.0;  // laminar_eta2(h), as the force pass
  template <class S>
  TALUS_PAIR_INLINE void pair(const sph::Pair& q, S& s) const {
    s.support -= sph::mass_at(nb, q) * sph::inv_density_at(nb, q) * sph::laminar_weight(q, eta2);  // dW/dr <= 0
  }
};
}  // namespace

double lattice_viscous_support(const World& world) {
  const KernelTable& kernel = world.kernel;
  const double dp = world.dp, radius = kernel.support_radius(), eta2 = sph::laminar_eta2(kernel.h());
  const int n = static_cast<int>(std::ceil(radius / dp));
  const int nz = world.dim == 3 ? n : 0;
  const double vol = std::pow(dp, world.dim);
  double sum = 0.0;
  for (int a = -n; a <= n; ++a)
    for (int b = -n; b <= n; ++b)
      for (int c = -nz; c <= nz; ++c) {
        const double r2 = dp * dp * (a * a + b * b + c * c);
        const double r = std::sqrt(r2);
        if (r2 == 0.0 || r >= radius) continue;
        sum += vol * std::abs(r * kernel.dw(r)) / (r2 + eta2);
      }
  return sum;
}

std::uint64_t WcsphStage::strain_rate_pass(World& world) {
  FluidFields f(world.fluid);
  auto shear = world.fluid.scalar("shear_rate");
  sph::Neighbours nb = f.neighbours();
  nb.inv_density = reciprocals<double>().data();
  const int dim = world.dim;
  auto start = [&](Index i) {
    StrainSums s;
    s.v = f.v[i];
    return s;
  };
  const std::span<const Vec3> x = f.x;
  const std::size_t owned = world.fluid.owned_size();  // the halo's rates come from their owners
  if (point_implicit_) {
    visc_support_.resize(x.size());
    double* support = visc_support_.data();
    auto finish = [&](Index i, const StrainSums& s) {
      shear[i] = sph::shear_rate_from_gradient(s.g, s.l, dim);
      support[i] = s.support;
    };
    return sph::pair_pass(owned, x, cells_, world.kernel, sph::same_set, start, finish,
                          sph::VelocityGradient{nb}, ViscousSupport{nb, sph::laminar_eta2(h_)});
  }
  auto finish = [&](Index i, const StrainSums& s) { shear[i] = sph::shear_rate_from_gradient(s.g, s.l, dim); };
  return sph::pair_pass(owned, x, cells_, world.kernel, sph::same_set, start, finish, sph::VelocityGradient{nb});
}

void WcsphStage::apparent_viscosity_pass(World& world) {
  FluidFields f(world.fluid);
  const auto shear = world.fluid.scalar("shear_rate");
  auto mu = world.fluid.scalar("mu_eff");
  const std::size_t n = mu.size();
  // Newtonian materials: their constant viscosity; the others: one batch call each.
  const double* mu_m = material_mu_.data();
#pragma omp parallel for schedule(static) if (n >= 4096)
  for (std::size_t i = 0; i < n; ++i) mu[i] = mu_m[f.mat[i]];
  const ViscosityInputs in{shear.data(), f.p.data(), f.rho.data()};
  for (int m : rheology_materials_)
    world.materials[m].rheology->apparent_viscosity(world.material_particles(m), in, mu.data());
  if (smagorinsky_) {
    const double l2 = (smagorinsky_cs_ * world.dp) * (smagorinsky_cs_ * world.dp);
#pragma omp parallel for schedule(static) if (n >= 4096)
    for (std::size_t i = 0; i < n; ++i) mu[i] += f.rho[i] * l2 * shear[i];
  }
  // The bound is over this rank's own particles (halo rows have part of their neighbours).
  const std::size_t owned = world.fluid.owned_size();
  const std::span<const double> inv_rho = reciprocals<double>();  // the three passes keep the fluid in double
  double nu_max = 0.0;
  if (point_implicit_) {
    // Inertia 1 + dt D_i; the explicit viscous bound then sees nu_i / (1 + dt D_i).
    inertia_.resize(n);
    double* inertia = inertia_.data();
    const double* support = visc_support_.data();
    const double dt = courant_ * h_ / c0_max_, s_bulk = bulk_viscous_support_;
#pragma omp parallel for schedule(static) reduction(max : nu_max) if (n >= 4096)
    for (std::size_t i = 0; i < n; ++i) {
      const double nu = mu[i] * inv_rho[i];
      inertia[i] = 1.0 + dt * 4.0 * nu * std::max(support[i], s_bulk);
      if (i < owned) nu_max = std::max(nu_max, nu / inertia[i]);
    }
  } else {
#pragma omp parallel for schedule(static) reduction(max : nu_max) if (n >= 4096)
    for (std::size_t i = 0; i < owned; ++i) nu_max = std::max(nu_max, mu[i] * inv_rho[i]);
  }
  nu_field_max_ = nu_max;
  // The force pass reads the neighbours' mu_eff: the halo's from their owners.
  static const std::string mu_eff[] = {"mu_eff"};
  world.parallel().refresh_halo(world.fluid, mu_eff);
}

void WcsphStage::scale_stiff_particles(World& world) {
  auto a = world.fluid.vector("acceleration");
  const double* inertia = inertia_.data();
  const std::size_t n = a.size();
#pragma omp parallel for schedule(static) if (n >= 4096)
  for (std::size_t i = 0; i < n; ++i) a[i] = a[i] * (1.0 / inertia[i]);
}

}  // namespace talus::wcsph
