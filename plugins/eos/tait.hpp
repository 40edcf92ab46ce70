// Tait equation of state (Batchelor 1967; Monaghan 1994, J. Comput. Phys. 110;
// the coastline seed, gamma = 7, as in DualSPHysics):
//   p = B ((rho/rho0)^gamma - 1),  B = rho0 c0^2 / gamma,
//   c = sqrt(dp/drho) = c0 (rho/rho0)^((gamma-1)/2),
//   rho(p) = rho0 (1 + p/B)^(1/gamma).
#pragma once

#include "talus/eos.hpp"

namespace talus::eos {

class Tait final : public EquationOfState {
 public:
  static ParamSet describe();
  explicit Tait(const ParamValues& v);

  void set_reference_density(double rho0) override;
  void pressure(std::span<const Index> idx, const double* rho, double* p, double* c) const override;
  double density_at(double p) const override;
  double reference_sound_speed() const override { return c0_; }

  double stiffness() const { return b_; }  // B, Pa

 private:
  double c0_, gamma_, rho0_ = 1000.0, b_ = 0.0;
};

}  // namespace talus::eos
