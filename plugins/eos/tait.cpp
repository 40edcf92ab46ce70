#include "tait.hpp"

#include <cmath>

namespace talus::eos {

ParamSet Tait::describe() {
  ParamSet p{"tait", "Tait equation of state p = B((rho/rho0)^gamma - 1), B = rho0 c0^2/gamma"};
  p.real("c0").unit("m/s").greater_than(0.0).doc(
      "numerical speed of sound at rho0; >= 10 x the largest flow speed keeps density variation below ~1%");
  p.real("gamma").greater_than(0.0).default_value(7.0).doc("polytropic index (7 for water)");
  return p;
}

Tait::Tait(const ParamValues& v) : c0_(v.real("c0")), gamma_(v.real("gamma")) { set_reference_density(rho0_); }

void Tait::set_reference_density(double rho0) {
  rho0_ = rho0;
  b_ = rho0 * c0_ * c0_ / gamma_;
}

void Tait::pressure(std::span<const Index> idx, const double* rho, double* p, double* c) const {
  const double inv_rho0 = 1.0 / rho0_, b = b_, g = gamma_, half_gm1 = 0.5 * (gamma_ - 1.0), c0 = c0_;
  const bool water = gamma_ == 7.0;  // the common case: integer powers, no pow()
#pragma omp parallel for schedule(static) if (idx.size() >= 4096)
  for (std::size_t k = 0; k < idx.size(); ++k) {
    const Index i = idx[k];
    const double s = rho[i] * inv_rho0;
    if (water) {
      const double s2 = s * s, s3 = s2 * s;
      p[i] = b * (s3 * s3 * s - 1.0);
      c[i] = c0 * s3;
    } else {
      p[i] = b * (std::pow(s, g) - 1.0);
      c[i] = c0 * std::pow(s, half_gm1);
    }
  }
}

double Tait::density_at(double p) const { return rho0_ * std::pow(1.0 + p / b_, 1.0 / gamma_); }

}  // namespace talus::eos
