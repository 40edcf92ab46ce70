#include "coulomb.hpp"

#include <cmath>
#include <numbers>

namespace talus::rheology {

ParamSet Coulomb::describe() {
  ParamSet p{"coulomb", "frictional basal stress (1 - r_u) rho g_n h tan(delta), depth-integrated flow"};
  p.real("friction_angle").unit("deg").min(0.0).less_than(90.0).doc("basal friction angle delta");
  p.real("pore_pressure_ratio").min(0.0).max(1.0).default_value(0.0)
      .doc("pore pressure ratio r_u = p_w / (rho g_n h)");
  return p;
}

Coulomb::Coulomb(const ParamValues& v)
    : tan_delta_((1.0 - v.real("pore_pressure_ratio")) *
                 std::tan(v.real("friction_angle") * std::numbers::pi / 180.0)) {}

void Coulomb::basal_shear(std::span<const Index> idx, const BasalInputs& in, double* tau) const {
  const double mu = tan_delta_;
  for (const Index i : idx) tau[i] = mu * in.density[i] * in.normal_gravity[i] * in.depth[i];
}

}  // namespace talus::rheology
