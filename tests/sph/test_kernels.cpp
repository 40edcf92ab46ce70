// Smoothing kernels: normalisation, gradient consistency and derivative of
// every kernel in 2D and 3D by radial quadrature, and the error of the host's
// tabulation (KernelTable) against the analytic kernel.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <memory>
#include <numbers>

#include "cubic_spline.hpp"
#include "muller.hpp"
#include "talus/kernel_table.hpp"
#include "wendland.hpp"

namespace {

using talus::SmoothingKernel;
constexpr double pi = std::numbers::pi;

// Composite Simpson on [a, b] with n (even) intervals.
double simpson(const std::function<double(double)>& f, double a, double b, int n = 4000) {
  const double h = (b - a) / n;
  double s = f(a) + f(b);
  for (int k = 1; k < n; ++k) s += f(a + k * h) * (k % 2 ? 4.0 : 2.0);
  return s * h / 3.0;
}

// Integral over the ball of radius `support` (q units) of a radial function in
// dimension dim, split at q = 1 where the cubic spline's pieces meet.
double radial_integral(const std::function<double(double)>& f, double support, int dim) {
  auto shell = [&](double q) { return f(q) * (dim == 2 ? 2.0 * pi * q : 4.0 * pi * q * q); };
  if (support <= 1.0) return simpson(shell, 0.0, support);
  return simpson(shell, 0.0, 1.0) + simpson(shell, 1.0, support);
}

std::unique_ptr<SmoothingKernel> make(const std::string& name) {
  const talus::ParamValues none;
  if (name == "cubic_spline") return std::make_unique<talus::kernels::CubicSpline>(none);
  if (name == "wendland_c2") return std::make_unique<talus::kernels::WendlandC2>(none);
  if (name == "wendland_c4") return std::make_unique<talus::kernels::WendlandC4>(none);
  return std::make_unique<talus::kernels::Muller>(none);
}

class KernelTest : public ::testing::TestWithParam<std::tuple<std::string, int>> {};

TEST_P(KernelTest, NormalisedToOne) {
  const auto [name, dim] = GetParam();
  const auto k = make(name);
  const double integral = k->value_norm(dim) * radial_integral([&](double q) { return k->value_shape(q); },
                                                               k->support(), dim);
  EXPECT_NEAR(integral, 1.0, 1e-6) << name << " in " << dim << "D";
}

// int x . grad W dV = int r dW/dr dV = -dim for a normalised kernel (by parts);
// for the Müller set this checks the spiky gradient's own normalisation.
TEST_P(KernelTest, GradientConsistency) {
  const auto [name, dim] = GetParam();
  const auto k = make(name);
  const double integral = k->gradient_norm(dim) * radial_integral([&](double q) { return q * k->gradient_shape(q); },
                                                                  k->support(), dim);
  EXPECT_NEAR(integral, -static_cast<double>(dim), 1e-6) << name << " in " << dim << "D";
}

// The gradient is the derivative of the value (not for Müller, whose
// gradient is the spiky kernel's by design).
TEST_P(KernelTest, GradientIsDerivativeOfValue) {
  const auto [name, dim] = GetParam();
  if (name == "muller") GTEST_SKIP() << "spiky gradient by design";
  const auto k = make(name);
  const double e = 1e-6;
  for (double q = 0.01; q < k->support() - 2 * e; q += 0.0137) {
    const double fd = (k->value_shape(q + e) - k->value_shape(q - e)) / (2 * e);
    EXPECT_NEAR(k->gradient_shape(q), fd, 1e-7) << name << " at q = " << q;
  }
  EXPECT_DOUBLE_EQ(k->gradient_norm(dim), k->value_norm(dim));
  EXPECT_EQ(k->value_shape(k->support()), 0.0);
  EXPECT_EQ(k->gradient_shape(k->support()), 0.0);
}

// Tabulation error: linear interpolation on 4096 intervals, O(dq^2 |f''|/8).
TEST_P(KernelTest, TableMatchesAnalytic) {
  const auto [name, dim] = GetParam();
  const auto k = make(name);
  const double h = 0.013;
  const talus::KernelTable table(*k, dim, h);
  const double hd = std::pow(h, dim);
  const double w_scale = k->value_norm(dim) / hd, dw_scale = k->gradient_norm(dim) / (hd * h);
  const double w_max = w_scale * k->value_shape(0.0);
  double dw_max = 0.0;
  for (double q = 0; q < k->support(); q += 1e-3) dw_max = std::max(dw_max, std::abs(dw_scale * k->gradient_shape(q)));
  double err_w = 0.0, err_dw = 0.0;
  for (int n = 0; n <= 10007; ++n) {
    const double q = k->support() * n / 10007.0 * 1.01;  // a little beyond the support too
    const double r = q * h;
    err_w = std::max(err_w, std::abs(table.w(r) - w_scale * k->value_shape(q)));
    err_dw = std::max(err_dw, std::abs(table.dw(r) - dw_scale * k->gradient_shape(q)));
  }
  EXPECT_LT(err_w / w_max, 1e-6) << name;
  EXPECT_LT(err_dw / dw_max, 1e-5) << name;  // the spline's f'' jumps at q = 1: first order there
  EXPECT_NEAR(table.support_radius(), k->support() * h, 1e-15);
  EXPECT_EQ(table.w(1.001 * k->support() * h), 0.0);
}

// dW/dr / r read from r^2, what the pair loops multiply x_i - x_j by: the gradient it gives, r times it, within
// 1e-5 of the largest |dW/dr| (the bound of the table over r above) from q = 0.1 on. Over r^2 the table is
// coarsest near r = 0, where g(q)/q has a sqrt(r^2) term; below q = 0.1 its error is larger but multiplied by
// r < 0.1 h in the gradient (and particles never come that close: they repel long before). Müller's spiky
// gradient is singular at 0 and is read from r.
TEST_P(KernelTest, GradientOverRFromR2MatchesAnalytic) {
  const auto [name, dim] = GetParam();
  const auto k = make(name);
  const double h = 0.013;
  const talus::KernelTable table(*k, dim, h);
  const double dw_scale = k->gradient_norm(dim) / (std::pow(h, dim) * h);
  double dw_max = 0.0, err = 0.0;
  for (int n = 0; n <= 10007; ++n) {
    const double q = 0.1 + (k->support() - 0.1) * n / 10007.0 * 1.01;  // a little beyond the support too
    const double r = q * h;
    const double exact = q < k->support() ? dw_scale * k->gradient_shape(q) : 0.0;
    dw_max = std::max(dw_max, std::abs(exact));
    err = std::max(err, std::abs(r * table.dw_over_r_from_r2(r * r) - exact));
  }
  EXPECT_LT(err / dw_max, 1e-5) << name;
  if (name != "muller")  // the limit at r = 0 (times h: dw_scale g(q)/q as q -> 0)
    EXPECT_NEAR(table.dw_over_r_from_r2(0.0) * h, dw_scale * k->gradient_shape(1e-9) / 1e-9, 1e-6 * dw_max) << name;
}

INSTANTIATE_TEST_SUITE_P(AllKernels, KernelTest,
                         ::testing::Combine(::testing::Values("cubic_spline", "wendland_c2", "wendland_c4", "muller"),
                                            ::testing::Values(2, 3)),
                         [](const auto& info) {
                           return std::get<0>(info.param) + "_" + std::to_string(std::get<1>(info.param)) + "d";
                         });

// The Müller viscosity kernel W_v (normalised, W_v(h) = W_v'(h) = 0) has the
// Laplacian the seed's eq. 19 gives: 45/(pi h^6)(h - r) in 3D, 40/(pi h^5)(h - r)
// in 2D. Check: W_v integrates to 1 and its Laplacian, by finite differences,
// matches the tabulated one.
TEST(MullerKernel, ViscosityLaplacianMatchesItsKernel) {
  const auto k = make("muller");
  const double h = 0.1;
  for (int dim : {2, 3}) {
    std::function<double(double)> wv;
    if (dim == 3)
      wv = [&](double r) {
        return 15.0 / (2.0 * pi * h * h * h) * (-r * r * r / (2 * h * h * h) + r * r / (h * h) + h / (2 * r) - 1.0);
      };
    else
      wv = [&](double r) {
        const double c = 40.0 / (pi * std::pow(h, 5));
        return c * (h * r * r / 4.0 - r * r * r / 9.0 - 5.0 * h * h * h / 36.0 - h * h * h / 6.0 * std::log(r / h));
      };
    // W_v is singular (integrably) at r = 0: integrate the shell from a tiny radius.
    auto shell = [&](double q) { return wv(q * h) * (dim == 2 ? 2.0 * pi * q : 4.0 * pi * q * q); };
    const double integral = simpson(shell, 1e-9, 1.0, 200000) * std::pow(h, dim);
    EXPECT_NEAR(integral, 1.0, 1e-4) << dim << "D";
    const talus::KernelTable table(*k, dim, h);
    for (double r = 0.1 * h; r < 0.95 * h; r += 0.05 * h) {
      const double e = 1e-4 * h;
      const double d2 = (wv(r + e) - 2 * wv(r) + wv(r - e)) / (e * e);
      const double d1 = (wv(r + e) - wv(r - e)) / (2 * e);
      const double lap = d2 + (dim - 1) / r * d1;
      EXPECT_NEAR(table.laplacian(r), lap, 1e-4 * std::abs(lap)) << dim << "D r/h = " << r / h;
    }
  }
}

}  // namespace
