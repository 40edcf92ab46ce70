// Linear equation of state of the rock-fluid seed (§3.2, eq. 17; Desbrun &
// Gascuel 1996): p = k (rho - rho0). The sound speed is c = sqrt(dp/drho) =
// sqrt(k) everywhere; rho(p) = rho0 + p/k.
#pragma once

#include "talus/eos.hpp"

namespace talus::eos {

class Linear final : public EquationOfState {
 public:
  static ParamSet describe();
  explicit Linear(const ParamValues& v);

  void set_reference_density(double rho0) override { rho0_ = rho0; }
  void pressure(std::span<const Index> idx, const double* rho, double* p, double* c) const override;
  double density_at(double p) const override { return rho0_ + p / k_; }
  double reference_sound_speed() const override { return c_; }

 private:
  double k_, c_, rho0_ = 1000.0;
};

}  // namespace talus::eos
