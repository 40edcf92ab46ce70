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
  // The same from r^2, for pair loops that have only r^2: read from a table over r^2 (no square root, no
  // division) when dW/dr / r is bounded at r = 0, as for every smooth kernel; otherwise (the spiky gradient
  // of the Mueller set, singular there) from dw(r) / r.
  TALUS_PAIR_INLINE double dw_over_r_from_r2(double r2) const {
    if (gradient_by_r2_) return interpolate(dw_r_by_r2_, r2 * inv_dr2_, size_r2_);
    const double r = std::sqrt(r2);
    return r > 0.0 ? dw(r) / r : 0.0;
  }
  // Whether dw_over_r_from_r2 reads the table over r^2 (every smooth kernel).
  bool gradient_by_r2() const { return gradient_by_r2_; }
  // The same read for n values of r^2 below support_radius()^2 when
  // gradient_by_r2(), without the range test: a loop the compiler vectorises.
  TALUS_PAIR_INLINE void dw_over_r_within_support(const double* __restrict r2, double* __restrict out, int n) const {
    const double* __restrict t = dw_r_by_r2_.data();
    const double scale = inv_dr2_;
    for (int k = 0; k < n; ++k) {
      const double s = r2[k] * scale;
      const int cell = static_cast<int>(s);
      out[k] = t[cell] + (s - cell) * (t[cell + 1] - t[cell]);
    }
  }
  // Laplacian-kernel value (0 unless the kernel has one).
  double laplacian(double r) const { return has_laplacian_ ? lookup(lap_, r) : 0.0; }
  bool has_laplacian() const { return has_laplacian_; }
  double w0() const { return w_[0]; }  // W(0), the self contribution

 private:
  TALUS_PAIR_INLINE double lookup(const std::vector<double>& t, double r) const {
    return interpolate(t, r * inv_dr_, size_);
  }
  // Linear interpolation at s table intervals from the start; 0 beyond the support.
  TALUS_PAIR_INLINE static double interpolate(const std::vector<double>& t, double s, int n) {
    const int k = static_cast<int>(s);
    if (k >= n) return 0.0;
    const double f = s - k;
    return t[k] + f * (t[k + 1] - t[k]);
  }

  std::vector<double> w_, dw_, lap_;  // size_ + 2 entries over r, zero beyond the support
  std::vector<double> dw_r_by_r2_;     // dW/dr / r, size_r2_ + 2 entries over r^2 (when gradient_by_r2_)
  double h_ = 0.0, support_ = 0.0, inv_dr_ = 0.0, inv_dr2_ = 0.0;
  bool gradient_by_r2_ = false;
  int dim_ = 3, size_ = 0, size_r2_ = 0;
  bool has_laplacian_ = false;
};

}  // namespace talus
