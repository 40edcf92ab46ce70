// Rheology plugins: batch calls over index spans of one material.
//
// Full SPH: the apparent (effective) dynamic viscosity mu_eff per particle
// from the shear rate |D| = sqrt(2 D:D) and the pressure (three-pass scheme of
// DESIGN.md: strain rate pair pass, this batch call, viscous force pair pass).
// Depth-integrated SPH: the basal shear stress tau_b(h, |v|) that resists the
// depth-averaged flow. A model implements one or both; the stage that needs a
// capability checks for it at setup and names the model if it is missing.
#pragma once

#include <span>

#include "talus/plugin.hpp"

namespace talus {

struct ViscosityInputs {
  const double* shear_rate;  // |D| = sqrt(2 D:D), 1/s
  const double* pressure;    // Pa
  const double* density;     // kg/m^3
};

struct BasalInputs {
  const double* depth;           // h, m
  const double* speed;           // |v| depth-averaged, m/s
  const double* density;         // kg/m^3
  const double* normal_gravity;  // g_n = g cos(theta) (plus curvature), m/s^2, > 0
};

class TALUS_API Rheology : public Model {
 public:
  ~Rheology() override;

  virtual bool has_apparent_viscosity() const { return false; }
  // True when mu_eff never depends on the flow: the stage then skips the
  // strain-rate pass and the batch call altogether.
  virtual bool is_newtonian() const { return false; }
  // Viscosity used for the viscous time-step bound when the actual mu_eff
  // field is not available (Pa s).
  virtual double reference_viscosity() const { return 0.0; }
  virtual void apparent_viscosity(std::span<const Index> idx, const ViscosityInputs& in, double* mu) const;

  virtual bool has_basal_shear() const { return false; }
  // Magnitude of the basal shear stress (Pa), acting against the velocity.
  virtual void basal_shear(std::span<const Index> idx, const BasalInputs& in, double* tau) const;
};

}  // namespace talus
