// Equation-of-state plugins work on whole index spans of one material's
// particles (DESIGN.md principle 1): one virtual call per material per step,
// a plain vectorisable loop inside.
#pragma once

#include <span>

#include "talus/plugin.hpp"

namespace talus {

class TALUS_API EquationOfState : public Model {
 public:
  ~EquationOfState() override;

  // Called once at setup with the material's reference density rho0.
  virtual void set_reference_density(double rho0) = 0;
  // p[i] and sound speed c[i] for every i in idx.
  virtual void pressure(std::span<const Index> idx, const double* rho, double* p, double* c) const = 0;
  // The inverse, rho(p); used to start a column in hydrostatic equilibrium.
  virtual double density_at(double p) const = 0;
  // Sound speed at the reference density, for the time-step estimate.
  virtual double reference_sound_speed() const = 0;
};

}  // namespace talus
