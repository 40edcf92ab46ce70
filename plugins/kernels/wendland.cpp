#include "wendland.hpp"

#include <numbers>

#include "talus/error.hpp"

namespace talus::kernels {

namespace {
constexpr double pi = std::numbers::pi;

[[noreturn]] void bad_dim(const char* name) {
  throw InputError(std::string(name) + ": the Wendland kernels are defined for dimension 2 or 3");
}
}  // namespace

ParamSet WendlandC2::describe() {
  return ParamSet{"wendland_c2", "Wendland C2 kernel, support 2h (coastline seed; DualSPHysics default)"};
}

double WendlandC2::value_shape(double q) const {
  if (q >= 2.0) return 0.0;
  const double t = 1.0 - 0.5 * q;
  const double t2 = t * t;
  return t2 * t2 * (2.0 * q + 1.0);
}

// d/dq [(1 - q/2)^4 (2q + 1)] = -5 q (1 - q/2)^3
double WendlandC2::gradient_shape(double q) const {
  if (q >= 2.0) return 0.0;
  const double t = 1.0 - 0.5 * q;
  return -5.0 * q * t * t * t;
}

double WendlandC2::value_norm(int dim) const {
  if (dim == 2) return 7.0 / (4.0 * pi);
  if (dim == 3) return 21.0 / (16.0 * pi);
  bad_dim("wendland_c2");
}

ParamSet WendlandC4::describe() {
  return ParamSet{"wendland_c4", "Wendland C4 (quintic-order) kernel, support 2h"};
}

double WendlandC4::value_shape(double q) const {
  if (q >= 2.0) return 0.0;
  const double t = 1.0 - 0.5 * q;
  const double t2 = t * t;
  return t2 * t2 * t2 * (35.0 / 12.0 * q * q + 3.0 * q + 1.0);
}

// d/dq [(1 - q/2)^6 (35/12 q^2 + 3q + 1)] = -(14/3) q (1 - q/2)^5 (1 + 5q/2)
double WendlandC4::gradient_shape(double q) const {
  if (q >= 2.0) return 0.0;
  const double t = 1.0 - 0.5 * q;
  const double t2 = t * t;
  return -(14.0 / 3.0) * q * t2 * t2 * t * (1.0 + 2.5 * q);
}

double WendlandC4::value_norm(int dim) const {
  if (dim == 2) return 9.0 / (4.0 * pi);
  if (dim == 3) return 495.0 / (256.0 * pi);
  bad_dim("wendland_c4");
}

}  // namespace talus::kernels
