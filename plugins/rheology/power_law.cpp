#include "power_law.hpp"

#include <algorithm>

namespace talus::rheology {

ParamSet PowerLaw::describe() {
  ParamSet p{"power_law", "power-law fluid mu = K |D|^(n-1)"};
  p.real("power_index").min(0.05).max(3.0).doc("power-law index n (n < 1 shear thinning, n > 1 thickening)");
  p.real("consistency").unit("Pa s^n").greater_than(0.0).doc("consistency K");
  p.real("min_shear_rate").unit("1/s").greater_than(0.0).default_value(1e-6)
      .doc("lower bound of the shear rate (bounds the viscosity at rest for n < 1)");
  return p;
}

PowerLaw::PowerLaw(const ParamValues& v)
    : power_index_(v.real("power_index")), consistency_(v.real("consistency")),
      min_shear_rate_(v.real("min_shear_rate")) {}

void PowerLaw::apparent_viscosity(std::span<const Index> idx, const ViscosityInputs& in, double* mu) const {
  for (const Index i : idx) mu[i] = power_law_viscosity(consistency_, power_index_, in.shear_rate[i], min_shear_rate_);
}

ParamSet HerschelBulkley::describe() {
  ParamSet p{"herschel_bulkley", "Herschel-Bulkley fluid tau = tau_y + K |D|^n, bi-viscosity below the yield"};
  p.real("yield_stress").unit("Pa").min(0.0).doc("yield stress tau_y");
  p.real("power_index").min(0.05).max(3.0).doc("power-law index n");
  p.real("consistency").unit("Pa s^n").greater_than(0.0).doc("consistency K");
  p.real("max_viscosity").unit("Pa s").greater_than(0.0).doc("viscosity of the unyielded (plug) material, cut-off");
  p.real("min_shear_rate").unit("1/s").greater_than(0.0).default_value(1e-6)
      .doc("lower bound of the shear rate in K gd^(n-1)");
  return p;
}

HerschelBulkley::HerschelBulkley(const ParamValues& v)
    : yield_stress_(v.real("yield_stress")), power_index_(v.real("power_index")), consistency_(v.real("consistency")),
      max_viscosity_(v.real("max_viscosity")), min_shear_rate_(v.real("min_shear_rate")) {}

void HerschelBulkley::apparent_viscosity(std::span<const Index> idx, const ViscosityInputs& in, double* mu) const {
  for (const Index i : idx) {
    const double gd = std::max(in.shear_rate[i], min_shear_rate_);
    const double m = yield_stress_ / gd + power_law_viscosity(consistency_, power_index_, gd, min_shear_rate_);
    mu[i] = std::min(m, max_viscosity_);
  }
}

}  // namespace talus::rheology
