#include "newtonian.hpp"

namespace talus::rheology {

ParamSet Newtonian::describe() {
  ParamSet p{"newtonian", "Newtonian fluid: constant viscosity; laminar basal shear 3 mu v / h"};
  p.real("viscosity").unit("Pa s").min(0.0).doc("dynamic viscosity mu");
  return p;
}

Newtonian::Newtonian(const ParamValues& v) : viscosity_(v.real("viscosity")) {}

void Newtonian::apparent_viscosity(std::span<const Index> idx, const ViscosityInputs&, double* mu) const {
  const double m = viscosity_;
#pragma omp simd
  for (std::size_t k = 0; k < idx.size(); ++k) mu[idx[k]] = m;
}

void Newtonian::basal_shear(std::span<const Index> idx, const BasalInputs& in, double* tau) const {
  const double m3 = 3.0 * viscosity_;
  for (const Index i : idx) {
    const double h = in.depth[i];
    tau[i] = h > 0.0 ? m3 * in.speed[i] / h : 0.0;
  }
}

}  // namespace talus::rheology
