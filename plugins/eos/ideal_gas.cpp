#include "ideal_gas.hpp"

#include <cmath>

namespace talus::eos {

ParamSet IdealGas::describe() {
  ParamSet p{"ideal_gas", "isothermal ideal-gas equation of state p = k rho (rock-fluid seed eq. 16)"};
  p.real("k").unit("m^2/s^2").greater_than(0.0).doc("gas constant times temperature: dp/drho, the square of the sound speed");
  return p;
}

IdealGas::IdealGas(const ParamValues& v) : k_(v.real("k")), c_(std::sqrt(k_)) {}

void IdealGas::pressure(std::span<const Index> idx, const double* rho, double* p, double* c) const {
  const double k = k_, cs = c_;
#pragma omp parallel for schedule(static) if (idx.size() >= 4096)
  for (std::size_t n = 0; n < idx.size(); ++n) {
    const Index i = idx[n];
    p[i] = k * rho[i];
    c[i] = cs;
  }
}

}  // namespace talus::eos
