#include "hbp.hpp"

#include <limits>

namespace talus::rheology {

ParamSet Hbp::describe() {
  ParamSet p{"hbp", "Herschel-Bulkley-Papanastasiou viscoplastic sediment (coastline seed §2.3.2)"};
  p.choice("yield", {"constant", "mohr_coulomb", "drucker_prager"})
      .default_value("constant")
      .doc("yield stress: constant yield_stress, or c + p tan(phi) (Mohr-Coulomb) or the matched Drucker-Prager cone");
  p.real("yield_stress").unit("Pa").min(0.0).default_value(0.0).doc("constant yield stress tau_y (yield: constant)");
  p.real("cohesion").unit("Pa").min(0.0).default_value(0.0).doc("cohesion c (yield: mohr_coulomb, drucker_prager)");
  p.real("friction_angle").unit("deg").min(0.0).max(89.0).default_value(0.0)
      .doc("internal friction angle phi (yield: mohr_coulomb, drucker_prager)");
  p.real("regularisation").unit("s").min(0.0).default_value(100.0).doc("Papanastasiou exponent m (seed: 100)");
  p.real("power_index").min(0.05).max(3.0).default_value(1.0).doc("power-law index n (n < 1 shear thinning)");
  p.real("consistency").unit("Pa s^n").greater_than(0.0).doc("consistency K (n = 1: the plastic viscosity)");
  p.real("min_shear_rate").unit("1/s").greater_than(0.0).default_value(1e-6)
      .doc("lower bound of the shear rate in K gd^(n-1) (bounds it at rest for n < 1)");
  p.choice("yield_pressure", {"total", "effective"})
      .default_value("total")
      .doc("pressure in the yield criterion: total p (the seed), or the skeleton's effective p (1 - rho_w/rho) "
           "(Terzaghi, hydrostatic pore water; Fourtakas & Rogers 2016)");
  p.real("pore_fluid_density").unit("kg/m^3").greater_than(0.0).default_value(1000.0)
      .doc("pore water density rho_w of yield_pressure: effective (sea water: 1029)");
  p.real("max_viscosity").unit("Pa s").greater_than(0.0).optional()
      .doc("cap mu_max of the unyielded (plug) viscosity, bi-viscosity; bounds the viscous step C h^2 rho/mu_max "
           "(rho h c0 keeps it >= the acoustic step); absent: no cap (plug viscosity tau_y m + K)");
  return p;
}

namespace {
YieldModel yield_model(const std::string& s) {
  if (s == "mohr_coulomb") return YieldModel::mohr_coulomb;
  if (s == "drucker_prager") return YieldModel::drucker_prager;
  return YieldModel::constant;
}
}  // namespace

Hbp::Hbp(const ParamValues& v)
    : yield_(YieldStress::make(yield_model(v.string("yield")), v.real("yield_stress"), v.real("cohesion"),
                               v.real("friction_angle"))),
      regularisation_(v.real("regularisation")),
      power_index_(v.real("power_index")),
      consistency_(v.real("consistency")),
      min_shear_rate_(v.real("min_shear_rate")),
      pore_density_(v.string("yield_pressure") == "effective" ? v.real("pore_fluid_density") : 0.0),
      max_viscosity_(v.has("max_viscosity") ? v.real("max_viscosity") : std::numeric_limits<double>::infinity()) {}

void Hbp::apparent_viscosity(std::span<const Index> idx, const ViscosityInputs& in, double* mu) const {
  const double m = regularisation_, n = power_index_, k = consistency_, gmin = min_shear_rate_;
  const double rho_w = pore_density_, mu_max = max_viscosity_;
  const YieldStress y = yield_;
  for (const Index i : idx) {
    const double gd = in.shear_rate[i];
    const double tau_y = y.at(effective_pressure(in.pressure[i], in.density[i], rho_w));
    mu[i] = cap_viscosity(tau_y * papanastasiou_factor(m, gd) + power_law_viscosity(k, n, gd, gmin), mu_max);
  }
}

}  // namespace talus::rheology
