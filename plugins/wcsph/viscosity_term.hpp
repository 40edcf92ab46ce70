// The viscous pair term of the scene, chosen once per pass and handed to the
// pass as a concrete type: nothing in the pair loop branches on the choice.
// The fluid-fluid pass and the fluid-wall passes take it from here, so every
// wall set sees the fluid's viscosity (mu_eff included) the same way.
//   fluid neighbours: artificial; laminar with mu_j of j's material; Laplacian;
//     with mu_eff per particle, the three-pass laminar term with the scene's mean.
//   wall neighbours: the same terms, the laminar one with mu_wall = mu_i
//     (no-slip; Sums carry mu = mu_eff[i] with the three-pass viscosity), and
//     every term reads the velocity viscosity sees (visc_nb).
#pragma once

#include <cstdint>
#include <stdexcept>
#include <type_traits>

#include "talus/kernel_table.hpp"
#include "talus/sph/fluid_terms.hpp"

namespace talus::wcsph {

enum class ViscosityModel { artificial, laminar, laplacian };
enum class Neighbour { fluid, wall };

struct ViscositySettings {
  ViscosityModel model = ViscosityModel::artificial;
  double alpha_h = 0.0;                 // alpha * h (artificial)
  const double* material_mu = nullptr;  // Pa s per material (laminar)
  double laminar_eta2 = 0.0;            // sph::laminar_eta2(h)
  bool per_particle = false;            // mu_eff per particle (three-pass viscosity)
  sph::ViscosityMean mean = sph::ViscosityMean::arithmetic;
  const KernelTable* kernel = nullptr;  // Laplacian
};

// Calls run(term) with the viscous term for neighbours `nb` (visc_nb: the same
// fields, with the velocity the viscosity sees) and returns what run returns.
// NB: the fields' NeighbourFields type; mu_eff per particle needs double.
template <Neighbour Side, class NB, class Run>
std::uint64_t with_viscosity_term(const ViscositySettings& v, const NB& nb, const NB& visc_nb, Run&& run) {
  if constexpr (Side == Neighbour::fluid) {
    if (v.per_particle) {
      if constexpr (!std::is_same_v<NB, sph::Neighbours>) {
        throw std::logic_error("the three-pass viscosity reads the fluid in double");
      } else {
        if (v.mean == sph::ViscosityMean::harmonic)
          return run(sph::LaminarViscosityField<sph::ViscosityMean::harmonic>{nb, v.laminar_eta2});
        return run(sph::LaminarViscosityField<sph::ViscosityMean::arithmetic>{nb, v.laminar_eta2});
      }
    }
  }
  switch (v.model) {
    // Against a wall the artificial term sees the wall's viscous velocity too:
    // its own unless the wall is free-slip (sph/boundary_pass.hpp).
    case ViscosityModel::artificial: return run(sph::ArtificialViscosity{Side == Neighbour::wall ? visc_nb : nb, v.alpha_h});
    case ViscosityModel::laminar:
      return run(sph::LaminarViscosity<Side == Neighbour::wall, NB>{visc_nb, v.material_mu, v.laminar_eta2});
    case ViscosityModel::laplacian: return run(sph::LaplacianViscosity{visc_nb, v.kernel, v.material_mu});
  }
  return 0;
}

}  // namespace talus::wcsph
