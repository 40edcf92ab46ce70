// Ideal-gas (isothermal) equation of state of the rock-fluid seed (§3.2,
// eq. 16; Müller et al. 2003): p = k rho, c = sqrt(k), rho(p) = p/k.
// The pressure never vanishes (p(rho0) = k rho0): only pressure differences
// push, so a hydrostatic start is not meaningful with this model; the seed
// itself prefers the linear form p = k (rho - rho0) for stability.
#pragma once

#include "talus/eos.hpp"

namespace talus::eos {

class IdealGas final : public EquationOfState {
 public:
  static ParamSet describe();
  explicit IdealGas(const ParamValues& v);

  void set_reference_density(double) override {}
  void pressure(std::span<const Index> idx, const double* rho, double* p, double* c) const override;
  double density_at(double p) const override { return p / k_; }
  double reference_sound_speed() const override { return c_; }

 private:
  double k_, c_;
};

}  // namespace talus::eos
