// Cubic B-spline kernel, support 2h (Monaghan & Lattanzio 1985; Monaghan 1992,
// Annu. Rev. Astron. Astrophys. 30, eq. 2.6):
//   f(q) = 1 - 3/2 q^2 + 3/4 q^3      0 <= q < 1
//          1/4 (2 - q)^3              1 <= q < 2
//   sigma_1 = 2/3, sigma_2 = 10/(7 pi), sigma_3 = 1/pi.
#pragma once

#include "talus/smoothing_kernel.hpp"

namespace talus::kernels {

class CubicSpline final : public SmoothingKernel {
 public:
  static ParamSet describe();
  explicit CubicSpline(const ParamValues&) {}

  double support() const override { return 2.0; }
  double value_shape(double q) const override;
  double value_norm(int dim) const override;
  double gradient_shape(double q) const override;
  double gradient_norm(int dim) const override { return value_norm(dim); }
};

}  // namespace talus::kernels
