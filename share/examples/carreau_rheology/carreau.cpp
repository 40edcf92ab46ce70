#include "carreau.hpp"

#include <cmath>

namespace example {

talus::ParamSet Carreau::describe() {
  talus::ParamSet p{"carreau", "Carreau shear-thinning fluid"};
  p.real("zero_shear_viscosity").unit("Pa s").greater_than(0.0).doc("mu_0, viscosity at vanishing shear rate");
  p.real("infinite_shear_viscosity").unit("Pa s").min(0.0).default_value(0.0).doc("mu_inf, viscosity at high shear rate");
  p.real("time_constant").unit("s").min(0.0).doc("lambda, inverse of the shear rate where thinning starts");
  p.real("flow_index").greater_than(0.0).max(1.0).doc("n, power-law index of the thinning region");
  p.check([](const talus::ParamValues& v, talus::Diagnostics& d) {
    if (v.real("infinite_shear_viscosity") > v.real("zero_shear_viscosity"))
      d.error(v, "infinite_shear_viscosity", "must not exceed zero_shear_viscosity (the fluid thins)");
  });
  return p;
}

Carreau::Carreau(const talus::ParamValues& v)
    : mu_0_(v.real("zero_shear_viscosity")),
      mu_inf_(v.real("infinite_shear_viscosity")),
      lambda_(v.real("time_constant")),
      n_(v.real("flow_index")) {}

double Carreau::viscosity(double shear_rate) const {
  const double x = lambda_ * shear_rate;
  return mu_inf_ + (mu_0_ - mu_inf_) * std::pow(1.0 + x * x, 0.5 * (n_ - 1.0));
}

void Carreau::apparent_viscosity(std::span<const talus::Index> idx, const talus::ViscosityInputs& in, double* mu) const {
  for (const talus::Index i : idx) mu[i] = viscosity(in.shear_rate[i]);
}

}  // namespace example

TALUS_PLUGIN("example-carreau", "1.0.0",
             talus::model_entry<example::Carreau>("rheology", "carreau", "Carreau shear-thinning fluid"));
