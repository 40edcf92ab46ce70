#include "voellmy.hpp"

namespace talus::rheology {

ParamSet Voellmy::describe() {
  ParamSet p{"voellmy", "Voellmy basal stress rho g_n h mu + rho g v^2 / xi, depth-integrated flow"};
  p.real("friction_coefficient").min(0.0).doc("dry friction coefficient mu");
  p.real("turbulence").unit("m/s^2").greater_than(0.0).doc("turbulence coefficient xi");
  p.real("gravity").unit("m/s^2").greater_than(0.0).default_value(9.81)
      .doc("gravity magnitude g of the turbulent term");
  return p;
}

Voellmy::Voellmy(const ParamValues& v)
    : mu_(v.real("friction_coefficient")), g_over_xi_(v.real("gravity") / v.real("turbulence")) {}

void Voellmy::basal_shear(std::span<const Index> idx, const BasalInputs& in, double* tau) const {
  const double mu = mu_, k = g_over_xi_;
  for (const Index i : idx) {
    const double v = in.speed[i];
    tau[i] = in.density[i] * (in.normal_gravity[i] * in.depth[i] * mu + k * v * v);
  }
}

}  // namespace talus::rheology
