#include "cubic_spline.hpp"

#include <numbers>

#include "talus/error.hpp"

namespace talus::kernels {

ParamSet CubicSpline::describe() {
  return ParamSet{"cubic_spline", "cubic B-spline kernel, support 2h (Monaghan 1992)"};
}

double CubicSpline::value_shape(double q) const {
  if (q < 1.0) return 1.0 - 1.5 * q * q + 0.75 * q * q * q;
  if (q < 2.0) {
    const double t = 2.0 - q;
    return 0.25 * t * t * t;
  }
  return 0.0;
}

double CubicSpline::gradient_shape(double q) const {
  if (q < 1.0) return -3.0 * q + 2.25 * q * q;
  if (q < 2.0) {
    const double t = 2.0 - q;
    return -0.75 * t * t;
  }
  return 0.0;
}

double CubicSpline::value_norm(int dim) const {
  switch (dim) {
    case 1: return 2.0 / 3.0;
    case 2: return 10.0 / (7.0 * std::numbers::pi);
    case 3: return 1.0 / std::numbers::pi;
  }
  throw InputError("cubic_spline: dimension must be 1, 2 or 3");
}

}  // namespace talus::kernels
