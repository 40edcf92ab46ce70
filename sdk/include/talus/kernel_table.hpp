// A tabulated smoothing kernel: a value, not static state, built once from a
// SmoothingKernel plugin and read inline in pair loops by linear
// interpolation on a fine table over q = r/h. The table error is bounded by a
// unit test (O(dq^2 |f''|), about 1e-8 relative with the default size).
#pragma once

#include <cmath>
#include <vector>

#include "talus/config.hpp"

namespace talus {

class SmoothingKernel;

class TALUS_API KernelTable {
 public:
  static constexpr int default_size = 4096;

  KernelTable() = default;
  KernelTable(const SmoothingKernel& kernel, int dim, double h, int size = default_size);

  double h() const { return h_; }
  int dim() const { return dim_; }
  double support_radius() const { return support_ * h_; }  // in metres
  double support() const { return support_; }             // in units of h

  // W(r) in 1/m^dim.
  TALUS_PAIR_INLINE double w(double r) const { return lookup(w_, r); }
  // dW/dr in 1/m^(dim+1) (negative inside the support). The gradient of W
  // with respect to x_i for a pair is dw(r) * (x_i - x_j) / r.
  TALUS_PAIR_INLINE double dw(double r) const { return lookup(dw_, r); }
  // dW/dr / r: what a pair loop multiplies (x_i - x_j) by. Finite at r = 0.
  double dw_over_r(double r) const { return r > 1e-12 * h_ ? dw(r) / r : 0.0; }
  // Laplacian-kernel value (0 unless the kernel has one).
  double laplacian(double r) const { return has_laplacian_ ? lookup(lap_, r) : 0.0; }
  bool has_laplacian() const { return has_laplacian_; }
  double w0() const { return w_[0]; }  // W(0), the self contribution

 private:
  TALUS_PAIR_INLINE double lookup(const std::vector<double>& t, double r) const {
    const double s = r * inv_dr_;
    const int k = static_cast<int>(s);
    if (k >= size_) return 0.0;
    const double f = s - k;
    return t[k] + f * (t[k + 1] - t[k]);
  }

  std::vector<double> w_, dw_, lap_;  // size_ + 2 entries, zero beyond the support
  double h_ = 0.0, support_ = 0.0, inv_dr_ = 0.0;
  int dim_ = 3, size_ = 0;
  bool has_laplacian_ = false;
};

}  // namespace talus
