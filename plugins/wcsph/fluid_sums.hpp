// What a fluid particle i carries through a force pass of the wcsph stage,
// and what it sums (the members the pair terms of sph/fluid_terms.hpp read).
#pragma once

#include <cstdint>

#include "talus/vec3.hpp"

namespace talus::wcsph {

struct FluidSums {
  Vec3 v;             // v_i
  double m = 0.0;     // m_i (the mutual pass gives j the reaction m_i ...)
  double rho = 0.0;   // rho_i
  double inv_rho = 0.0;  // 1/rho_i
  double p = 0.0;     // p_i
  double c = 0.0;     // c_i
  double mu = 0.0;    // dynamic viscosity of i: its material's, or mu_eff[i] with the three-pass viscosity
  double kh = 0.0;    // rho_i / c_i^2: hydrostatic density gradient per unit g.dx (Fourtakas)
  std::int32_t mat = 0;  // material of i (density diffusion acts within one material)
  Vec3 acc;           // sum of accelerations, m/s^2
  double drho = 0.0;  // sum of density rates, kg/m^3/s
  double visc = 0.0;  // max |v_ij . dx| / (r^2 + eta^2), 1/s (time-step bound)
};

// The sums of a pass against a rigid body's wall set: also the moment of the
// pair forces (sph::WithPairMoment).
struct BodySums : FluidSums {
  Vec3 moment;
};

}  // namespace talus::wcsph
