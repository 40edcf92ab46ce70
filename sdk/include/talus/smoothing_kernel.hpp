// Smoothing-kernel plugins describe a kernel; they are never called in a pair
// loop. The host tabulates them once into a KernelTable (kernel_table.hpp)
// that the hot loops read inline, so a third-party kernel runs as fast as a
// built-in one (DESIGN.md, "Fast loops").
//
// With q = r/h the kernel is W(r, h) = sigma_d / h^d * f(q) on q < support().
// Schemes that use a different kernel for gradients (Müller et al. 2003: poly6
// for density, spiky for pressure gradients) return that one's shape from
// gradient_shape(); for ordinary kernels it is f'(q).
#pragma once

#include "talus/plugin.hpp"

namespace talus {

class TALUS_API SmoothingKernel : public Model {
 public:
  ~SmoothingKernel() override;

  virtual double support() const = 0;                   // q_max, e.g. 2 for Wendland C2
  virtual double value_shape(double q) const = 0;       // f(q)
  virtual double value_norm(int dim) const = 0;         // sigma_d of f
  virtual double gradient_shape(double q) const = 0;    // g(q), dW/dr = sigma_g / h^(d+1) g(q)
  virtual double gradient_norm(int dim) const = 0;      // sigma_g of g
  // Optional Laplacian shape for schemes that use one (Müller viscosity
  // kernel): returns false when the kernel has none.
  virtual bool has_laplacian() const { return false; }
  virtual double laplacian_shape(double /*q*/) const { return 0.0; }
  virtual double laplacian_norm(int /*dim*/) const { return 0.0; }
};

}  // namespace talus
