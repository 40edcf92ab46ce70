// Passes 1 and 2 of the three-pass non-Newtonian viscosity (DESIGN.md, "Non-
// Newtonian viscosity is three passes"); pass 3 is the force pass of
// fluid_pass.cpp with sph::LaminarViscosityField. None of this runs for a
// scene whose materials are all Newtonian without eddy viscosity.
//
// Eddy viscosity: the Smagorinsky model in the SPS form of Dalrymple & Rogers
// (2006, Coast. Eng. 53) as DualSPHysics uses it (the coastline seed's
// mu = mu_d + mu_t, §2.3.2): mu_t = rho (Cs dp)^2 |S|, |S| = sqrt(2 S:S), the
// filter width the particle spacing.
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
};
}  // namespace

std::uint64_t WcsphStage::strain_rate_pass(World& world) {
  FluidFields f(world.fluid);
  auto shear = world.fluid.scalar("shear_rate");
  sph::Neighbours nb = f.neighbours();
  nb.inv_density = inv_rho_.data();
  const int dim = world.dim;
  auto start = [&](Index i) {
    StrainSums s;
    s.v = f.v[i];
    return s;
  };
  auto finish = [&](Index i, const StrainSums& s) { shear[i] = sph::shear_rate_from_gradient(s.g, s.l, dim); };
  const std::span<const Vec3> x = f.x;
  return sph::pair_pass(x.size(), x, cells_, x, world.kernel, sph::same_set, start, finish,
                        sph::VelocityGradient{nb});
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
  double nu_max = 0.0;
#pragma omp parallel for schedule(static) reduction(max : nu_max) if (n >= 4096)
  for (std::size_t i = 0; i < n; ++i) nu_max = std::max(nu_max, mu[i] * inv_rho_[i]);
  nu_field_max_ = nu_max;
}

}  // namespace talus::wcsph
