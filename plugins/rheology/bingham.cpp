#include "bingham.hpp"

#include <cmath>
#include <limits>
#include <numbers>

#include "bingham_basal.hpp"
#include "hbp_formula.hpp"

namespace talus::rheology {

ParamSet Bingham::describe() {
  ParamSet p{"bingham", "Bingham fluid: Papanastasiou-regularised viscosity; infinite-landslide basal shear"};
  p.real("yield_stress").unit("Pa").min(0.0).doc("yield stress tau_y");
  p.real("viscosity").unit("Pa s").greater_than(0.0).doc("plastic viscosity mu_p");
  p.real("regularisation").unit("s").greater_than(0.0).default_value(100.0)
      .doc("Papanastasiou exponent m of the regularised apparent viscosity");
  p.choice("basal", {"exact", "pastor"}).default_value("exact")
      .doc("basal shear: exact cubic root, or Pastor's quadratic approximation (seed eq. 13)");
  p.real("basal_friction_angle").unit("deg").min(0.0).less_than(90.0).default_value(0.0)
      .doc("depth-integrated flow only: a Coulomb term rho g_n h tan(phi) on the basal normal stress added to the "
           "Bingham basal shear (the frictional Bingham law of the seed's practical slope)");
  p.real("max_viscosity").unit("Pa s").greater_than(0.0).optional()
      .doc("cap mu_max of the plug viscosity (bi-viscosity), bounds the viscous step C h^2 rho/mu_max; "
           "absent: no cap (plug viscosity mu_p + tau_y m)");
  return p;
}

Bingham::Bingham(const ParamValues& v)
    : yield_stress_(v.real("yield_stress")),
      viscosity_(v.real("viscosity")),
      regularisation_(v.real("regularisation")),
      max_viscosity_(v.has("max_viscosity") ? v.real("max_viscosity") : std::numeric_limits<double>::infinity()),
      pastor_(v.string("basal") == "pastor"),
      tan_friction_(std::tan(v.real("basal_friction_angle") * std::numbers::pi / 180.0)) {}

void Bingham::apparent_viscosity(std::span<const Index> idx, const ViscosityInputs& in, double* mu) const {
  const double mp = viscosity_, ty = yield_stress_, m = regularisation_, mu_max = max_viscosity_;
  for (const Index i : idx) mu[i] = cap_viscosity(mp + ty * papanastasiou_factor(m, in.shear_rate[i]), mu_max);
}

void Bingham::basal_shear(std::span<const Index> idx, const BasalInputs& in, double* tau) const {
  const double ty = yield_stress_, six_mu = 6.0 * viscosity_, tf = tan_friction_;
  if (ty <= 0.0) {  // no yield stress: the Newtonian laminar limit 3 mu v / h
    for (const Index i : idx) tau[i] = in.depth[i] > 0.0 ? 0.5 * six_mu * in.speed[i] / in.depth[i] : 0.0;
  } else {
    for (const Index i : idx) {
      const double h = in.depth[i];
      const double a = h > 0.0 ? six_mu * in.speed[i] / (ty * h) : 0.0;
      const double eta = pastor_ ? bingham_plug_ratio_pastor(a) : bingham_plug_ratio_exact(a);
      tau[i] = ty / eta;
    }
  }
  if (tf > 0.0)
    for (const Index i : idx) tau[i] += in.density[i] * in.normal_gravity[i] * in.depth[i] * tf;
}

}  // namespace talus::rheology
