// Power-law (Ostwald-de Waele) fluid: mu_eff = K gd^(n-1), gd = |D| bounded
// below by min_shear_rate (n < 1 diverges at rest). Units: K in Pa s^n.
// The hbp model with zero yield stress (hbp_formula.hpp); n = 1: Newtonian.
#pragma once

#include "hbp_formula.hpp"
#include "talus/rheology.hpp"

namespace talus::rheology {

class PowerLaw final : public Rheology {
 public:
  static ParamSet describe();
  explicit PowerLaw(const ParamValues& v);

  bool has_apparent_viscosity() const override { return true; }
  double reference_viscosity() const override { return consistency_; }
  void apparent_viscosity(std::span<const Index> idx, const ViscosityInputs& in, double* mu) const override;

 private:
  double power_index_, consistency_, min_shear_rate_;
};

// Herschel-Bulkley fluid: tau = tau_y + K gd^n above the yield stress, as the
// apparent viscosity mu_eff = min(tau_y / gd + K gd^(n-1), max_viscosity)
// (bi-viscosity cut-off below the yield, O'Donoghue et al. 1985 style). The
// limit m -> inf of hbp where m gd >> 1.
class HerschelBulkley final : public Rheology {
 public:
  static ParamSet describe();
  explicit HerschelBulkley(const ParamValues& v);

  bool has_apparent_viscosity() const override { return true; }
  double reference_viscosity() const override { return consistency_; }
  void apparent_viscosity(std::span<const Index> idx, const ViscosityInputs& in, double* mu) const override;

 private:
  double yield_stress_, power_index_, consistency_, max_viscosity_, min_shear_rate_;
};

}  // namespace talus::rheology
