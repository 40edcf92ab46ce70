// Wendland kernels, support 2h, q = r/h (Wendland 1995, Adv. Comput. Math. 4;
// normalisations as in Dehnen & Aly 2012, MNRAS 425, table 1, rescaled to
// support 2h).
//   C2 (the coastline seed's kernel, seed eq. for W(R, l_s)):
//       f(q) = (1 - q/2)^4 (2q + 1),               sigma_2 = 7/(4 pi), sigma_3 = 21/(16 pi)
//   C4: f(q) = (1 - q/2)^6 (35/12 q^2 + 3q + 1),   sigma_2 = 9/(4 pi), sigma_3 = 495/(256 pi)
// Both are positive definite in 2D and 3D only.
#pragma once

#include "talus/smoothing_kernel.hpp"

namespace talus::kernels {

class WendlandC2 final : public SmoothingKernel {
 public:
  static ParamSet describe();
  explicit WendlandC2(const ParamValues&) {}

  double support() const override { return 2.0; }
  double value_shape(double q) const override;
  double value_norm(int dim) const override;
  double gradient_shape(double q) const override;
  double gradient_norm(int dim) const override { return value_norm(dim); }
};

class WendlandC4 final : public SmoothingKernel {
 public:
  static ParamSet describe();
  explicit WendlandC4(const ParamValues&) {}

  double support() const override { return 2.0; }
  double value_shape(double q) const override;
  double value_norm(int dim) const override;
  double gradient_shape(double q) const override;
  double gradient_norm(int dim) const override { return value_norm(dim); }
};

}  // namespace talus::kernels
