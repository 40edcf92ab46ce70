// Newtonian fluid: constant dynamic viscosity mu.
// Full SPH: mu_eff = mu. Depth-integrated flow: laminar basal shear of a
// parabolic (Nusselt) profile, tau_b = 3 mu v / h (Pastor et al. 2009,
// Int. J. Numer. Anal. Meth. Geomech. 33, the Newtonian case of the
// infinite-landslide hypothesis, seed pfe-ie §2.2.2).
#pragma once

#include "talus/rheology.hpp"

namespace talus::rheology {

class Newtonian final : public Rheology {
 public:
  static ParamSet describe();
  explicit Newtonian(const ParamValues& v);

  bool has_apparent_viscosity() const override { return true; }
  bool is_newtonian() const override { return true; }
  double reference_viscosity() const override { return viscosity_; }
  void apparent_viscosity(std::span<const Index> idx, const ViscosityInputs& in, double* mu) const override;

  bool has_basal_shear() const override { return true; }
  void basal_shear(std::span<const Index> idx, const BasalInputs& in, double* tau) const override;

  double viscosity() const { return viscosity_; }

 private:
  double viscosity_;
};

}  // namespace talus::rheology
