#include "talus/kernel_table.hpp"

#include <cmath>
#include <stdexcept>

#include "talus/smoothing_kernel.hpp"

namespace talus {

KernelTable::KernelTable(const SmoothingKernel& kernel, int dim, double h, int size)
    : h_(h), support_(kernel.support()), dim_(dim), size_(size), has_laplacian_(kernel.has_laplacian()) {
  if (!(h > 0.0) || size < 16 || !(support_ > 0.0)) throw std::logic_error("KernelTable: bad h, size or support");
  const double dq = support_ / size;
  inv_dr_ = 1.0 / (dq * h);
  const double hd = std::pow(h, dim);
  const double w_scale = kernel.value_norm(dim) / hd;
  const double dw_scale = kernel.gradient_norm(dim) / (hd * h);
  const double lap_scale = has_laplacian_ ? kernel.laplacian_norm(dim) / (hd * h * h) : 0.0;
  w_.assign(size + 2, 0.0);
  dw_.assign(size + 2, 0.0);
  lap_.assign(has_laplacian_ ? size + 2 : 0, 0.0);
  for (int k = 0; k < size; ++k) {
    const double q = k * dq;
    w_[k] = w_scale * kernel.value_shape(q);
    dw_[k] = dw_scale * kernel.gradient_shape(q);
    if (has_laplacian_) lap_[k] = lap_scale * kernel.laplacian_shape(q);
  }
  // Entries size_ and size_+1 stay zero: every kernel vanishes at its support.

  // dW/dr / r over r^2. Bounded at r = 0 when g(q)/q tends to a limit (g(0) = 0 with a finite slope): then the
  // first entry is that limit, read at a q far below the table spacing.
  const double q_small = 1e-7 * dq;
  const double limit = kernel.gradient_shape(q_small) / q_small;
  gradient_by_r2_ = std::isfinite(limit) && std::abs(kernel.gradient_shape(0.0)) <= 1e-12 * std::abs(limit);
  if (gradient_by_r2_) {
    size_r2_ = 2 * size;
    const double ds = support_ * support_ / size_r2_;  // in units of h^2
    inv_dr2_ = 1.0 / (ds * h * h);
    dw_r_by_r2_.assign(size_r2_ + 2, 0.0);
    dw_r_by_r2_[0] = dw_scale * limit / h;
    for (int k = 1; k < size_r2_; ++k) {
      const double q = std::sqrt(k * ds);
      dw_r_by_r2_[k] = dw_scale * kernel.gradient_shape(q) / (q * h);
    }
  }
}

}  // namespace talus
