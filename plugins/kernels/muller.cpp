#include "muller.hpp"

#include <numbers>

#include "talus/error.hpp"

namespace talus::kernels {

namespace {
constexpr double pi = std::numbers::pi;

[[noreturn]] void bad_dim() { throw InputError("muller: the Müller kernels are defined for dimension 2 or 3"); }
}  // namespace

ParamSet Muller::describe() {
  return ParamSet{"muller",
                  "Müller et al. 2003 set: poly6 value, spiky gradient, viscosity Laplacian; support h (rock-fluid seed)"};
}

double Muller::value_shape(double q) const {
  if (q >= 1.0) return 0.0;
  const double t = 1.0 - q * q;
  return t * t * t;
}

double Muller::value_norm(int dim) const {
  if (dim == 2) return 4.0 / pi;
  if (dim == 3) return 315.0 / (64.0 * pi);
  bad_dim();
}

double Muller::gradient_shape(double q) const {
  if (q >= 1.0) return 0.0;
  const double t = 1.0 - q;
  return -3.0 * t * t;
}

double Muller::gradient_norm(int dim) const {
  if (dim == 2) return 10.0 / pi;
  if (dim == 3) return 15.0 / pi;
  bad_dim();
}

double Muller::laplacian_norm(int dim) const {
  if (dim == 2) return 40.0 / pi;
  if (dim == 3) return 45.0 / pi;
  bad_dim();
}

}  // namespace talus::kernels
