// Bingham viscoplastic fluid.
// Full SPH: Papanastasiou-regularised apparent viscosity
//   mu_eff = mu_p + tau_y (1 - exp(-m |D|)) / |D|   (-> mu_p + tau_y m at |D| = 0)
// (Papanastasiou 1987, J. Rheol. 31; seed sph-liquid-sediment §HBP with n = 1),
// optionally capped, mu_eff = min(mu_eff, max_viscosity): the bi-viscosity
// plug that bounds the viscous time step (hbp_formula.hpp, cap_viscosity).
// Depth-integrated flow: basal shear tau_b = tau_y / eta from the infinite
// landslide relation (seed pfe-ie §2.2.2 eqs 10-13), solved exactly by
// default or with Pastor's quadratic (`basal: pastor`), see bingham_basal.hpp;
// with basal_friction_angle phi the frictional Bingham law
// tau_b + rho g_n h tan(phi) (Coulomb friction on the basal normal stress).
#pragma once

#include "talus/rheology.hpp"

namespace talus::rheology {

class Bingham final : public Rheology {
 public:
  static ParamSet describe();
  explicit Bingham(const ParamValues& v);

  bool has_apparent_viscosity() const override { return true; }
  double reference_viscosity() const override { return viscosity_; }
  void apparent_viscosity(std::span<const Index> idx, const ViscosityInputs& in, double* mu) const override;

  bool has_basal_shear() const override { return true; }
  void basal_shear(std::span<const Index> idx, const BasalInputs& in, double* tau) const override;

 private:
  double yield_stress_, viscosity_, regularisation_, max_viscosity_;
  bool pastor_;
  double tan_friction_;  // basal Coulomb term (depth-integrated only)
};

}  // namespace talus::rheology
