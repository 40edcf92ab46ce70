// The kernel set of Müller, Charypar & Gross 2003 (SCA, eqs. 20-22), used by
// the rock-fluid seed (§3.2, eqs. 13, 15, 19). Support h (q = r/h <= 1): with
// this kernel the scene's h is the support radius, so choose h_over_dp ~ 3.
//   value (poly6, seed eq. 13):     f(q) = (1 - q^2)^3,  sigma_3 = 315/(64 pi), sigma_2 = 4/pi
//   gradient (spiky, seed eq. 15):  dW/dr = -sigma_s/h^(d+1) 3 (1 - q)^2,
//                                   sigma_s,3 = 15/pi, sigma_s,2 = 10/pi (spiky normalisation)
//   Laplacian (viscosity, seed eq. 19): lap W = sigma_l/h^(d+2) (1 - q),
//                                   sigma_l,3 = 45/pi, sigma_l,2 = 40/pi
// The spiky gradient keeps a repulsive pressure force as r -> 0, where the
// poly6 gradient vanishes.
#pragma once

#include "talus/smoothing_kernel.hpp"

namespace talus::kernels {

class Muller final : public SmoothingKernel {
 public:
  static ParamSet describe();
  explicit Muller(const ParamValues&) {}

  double support() const override { return 1.0; }
  double value_shape(double q) const override;
  double value_norm(int dim) const override;
  double gradient_shape(double q) const override;
  double gradient_norm(int dim) const override;
  bool has_laplacian() const override { return true; }
  double laplacian_shape(double q) const override { return q < 1.0 ? 1.0 - q : 0.0; }
  double laplacian_norm(int dim) const override;
};

}  // namespace talus::kernels
