// Voellmy basal resistance: dry friction plus turbulent drag,
//   tau_b = rho g_n h mu + rho g |v|^2 / xi
// (Voellmy 1955; Hungr 1995; Pastor et al. 2009). g in the drag term is the
// gravity magnitude (declared parameter; BasalInputs carries only g_n).
// Steady flow on an infinite incline: v = sqrt(xi h (sin theta - mu cos theta)).
#pragma once

#include "talus/rheology.hpp"

namespace talus::rheology {

class Voellmy final : public Rheology {
 public:
  static ParamSet describe();
  explicit Voellmy(const ParamValues& v);

  bool has_basal_shear() const override { return true; }
  void basal_shear(std::span<const Index> idx, const BasalInputs& in, double* tau) const override;

 private:
  double mu_, g_over_xi_;
};

}  // namespace talus::rheology
