// Carreau generalised-Newtonian fluid (Carreau 1972, Trans. Soc. Rheol.
// 16:99):
//
//   mu(gamma_dot) = mu_inf + (mu_0 - mu_inf) (1 + (lambda gamma_dot)^2)^((n - 1) / 2)
//
// with gamma_dot = |D| = sqrt(2 D:D). Shear-thinning for n < 1; n = 1 or
// lambda = 0 gives a Newtonian fluid of viscosity mu_0.
#pragma once

#include "talus/rheology.hpp"

namespace example {

class Carreau final : public talus::Rheology {
 public:
  static talus::ParamSet describe();
  explicit Carreau(const talus::ParamValues& values);

  bool has_apparent_viscosity() const override { return true; }
  double reference_viscosity() const override { return mu_0_; }
  // One call per material per step over its particles: a plain loop inside.
  void apparent_viscosity(std::span<const talus::Index> idx, const talus::ViscosityInputs& in,
                          double* mu) const override;

  double viscosity(double shear_rate) const;

 private:
  double mu_0_, mu_inf_, lambda_, n_;
};

}  // namespace example
