// The host's tabulated kernel (built for the smoothing length h0) read at any
// smoothing length l: W(r, l) = (h0/l)^2 W_table(r h0 / l) in 2D, and
// dW/dr(r, l) = (h0/l)^3 dW_table(r h0 / l). This keeps every kernel plugin
// usable with a smoothing length that follows the depth.
#pragma once

#include "talus/kernel_table.hpp"

namespace talus::runout {

struct VariableKernel {
  const KernelTable* table = nullptr;
  double h0 = 1.0;
  double support = 2.0;  // in units of the smoothing length

  explicit VariableKernel(const KernelTable& t) : table(&t), h0(t.h()), support(t.support()) {}
  VariableKernel() = default;

  double w(double r, double l) const {
    const double s = h0 / l;
    return s * s * table->w(r * s);
  }
  // dW/dr / r, finite at r = 0.
  double dw_over_r(double r, double l) const {
    const double s = h0 / l;
    return s * s * s * s * table->dw_over_r(r * s);
  }
};

}  // namespace talus::runout
