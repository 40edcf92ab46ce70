// Herschel-Bulkley-Papanastasiou (HBP) sediment rheology of the coastline seed
// (§2.3.2, Table 3; Fourtakas & Rogers 2016 as in DualSPHysics):
//   mu_eff = tau_y (1 - exp(-m gd)) / gd + K gd^(n-1),   gd = |D| = sqrt(2 D:D)
// with the yield stress constant or pressure dependent (Mohr-Coulomb or
// Drucker-Prager from cohesion c and friction angle phi), see hbp_formula.hpp.
// Units: tau_y, c in Pa; K in Pa s^n; m in s; phi in degrees.
// Limits: m = 0, n = 1: Newtonian mu = K; n = 1: Bingham (plugin bingham);
// tau_y = 0: power law; m -> inf: Herschel-Bulkley.
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
};

}  // namespace talus::rheology
