// Frictional (Coulomb) basal resistance with a pore-pressure ratio:
//   tau_b = (1 - r_u) rho g_n h tan(delta)
// (Hungr 1995, Can. Geotech. J. 32; Pastor et al. 2009 eq. for the
// frictional fluid; r_u = p_w / (rho g_n h)). The stress does not depend on
// the speed: at rest it is the largest static resistance.
#pragma once

#include "talus/rheology.hpp"

namespace talus::rheology {

class Coulomb final : public Rheology {
 public:
  static ParamSet describe();
  explicit Coulomb(const ParamValues& v);

  bool has_basal_shear() const override { return true; }
  void basal_shear(std::span<const Index> idx, const BasalInputs& in, double* tau) const override;

  double friction_coefficient() const { return tan_delta_; }  // (1 - r_u) tan(delta)

 private:
  double tan_delta_;
};

}  // namespace talus::rheology
