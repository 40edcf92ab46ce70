#include "linear.hpp"

#include <cmath>

namespace talus::eos {

ParamSet Linear::describe() {
  ParamSet p{"linear", "linear equation of state p = k (rho - rho0) (rock-fluid seed eq. 17)"};
  p.real("k").unit("m^2/s^2").greater_than(0.0).doc("stiffness dp/drho, the square of the sound speed");
  return p;
}

Linear::Linear(const ParamValues& v) : k_(v.real("k")), c_(std::sqrt(k_)) {}

void Linear::pressure(std::span<const Index> idx, const double* rho, double* p, double* c) const {
  const double k = k_, rho0 = rho0_, cs = c_;
#pragma omp parallel for schedule(static) if (idx.size() >= 4096)
  for (std::size_t n = 0; n < idx.size(); ++n) {
    const Index i = idx[n];
    p[i] = k * (rho[i] - rho0);
    c[i] = cs;
  }
}

}  // namespace talus::eos
