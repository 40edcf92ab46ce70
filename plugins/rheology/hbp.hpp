// Herschel-Bulkley-Papanastasiou (HBP) sediment rheology of the coastline seed
// (§2.3.2, Table 3; Fourtakas & Rogers 2016 as in DualSPHysics):
//   mu_eff = tau_y (1 - exp(-m gd)) / gd + K gd^(n-1),   gd = |D| = sqrt(2 D:D)
// with the yield stress constant or pressure dependent (Mohr-Coulomb or
// Drucker-Prager from cohesion c and friction angle phi), see hbp_formula.hpp.
// Units: tau_y, c in Pa; K in Pa s^n; m in s; phi in degrees.
// Limits: m = 0, n = 1: Newtonian mu = K; n = 1: Bingham (plugin bingham);
// tau_y = 0: power law; m -> inf: Herschel-Bulkley.
// Sediment options (Fourtakas & Rogers 2016, Adv. Water Resour. 92):
//   yield_pressure: effective -> the criterion sees the skeleton pressure
//     p' = p (1 - rho_w / rho) instead of p (hbp_formula.hpp, effective_pressure);
//   max_viscosity mu_max -> mu_eff = min(mu_HBP, mu_max), the bi-viscosity cap
//     of the unyielded region that bounds the viscous time step (cap_viscosity).
#pragma once

#include "hbp_formula.hpp"
#include "talus/rheology.hpp"

namespace talus::rheology {

class Hbp final : public Rheology {
 public:
  static ParamSet describe();
  explicit Hbp(const ParamValues& v);

  bool has_apparent_viscosity() const override { return true; }
  double reference_viscosity() const override { return consistency_; }
  void apparent_viscosity(std::span<const Index> idx, const ViscosityInputs& in, double* mu) const override;

 private:
  YieldStress yield_;
  double regularisation_, power_index_, consistency_, min_shear_rate_;
  double pore_density_;   // rho_w of the effective pressure, 0: total pressure
  double max_viscosity_;  // mu_max, +inf when not capped
};

}  // namespace talus::rheology
