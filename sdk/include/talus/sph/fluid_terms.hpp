// Pair terms of weakly compressible SPH (Monaghan 1994/2005; the coastline
// seed §2.3 as implemented by DualSPHysics, Domínguez et al. 2022), written
// once and used by the fluid-fluid pass of the wcsph stage and by the
// fluid-wall passes over the wall sets of boundary models. i is the particle
// summing, j its neighbour; dx = x_i - x_j, grad = grad_i W_ij. Each term
// reads the neighbour's fields through the accessors below (velocity_at(nb, q)
// and the like, never nb's pointers): NB is a NeighbourFields view (in double,
// or in float in mixed precision; the arithmetic is double), its uniform form,
// or its gathered form, whose values come with the Pair. The i-state comes from
// the pass's Sums (duck-typed members: v, m, rho, inv_rho, p, c, mu, kh, mat;
// the sums acc, drho, visc). The terms of the fluid-fluid pass also have the
// mutual form of sph/mutual_pass.hpp: one evaluation per pair, j's share
// added to a PairReaction r. A pair's |v_ij . x_ij|/(r^2 + eta^2) is the same
// for j, and only the largest of any pair bounds the time step: s.visc alone
// takes it.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "talus/sph/neighbour_records.hpp"
#include "talus/sph/pair_loop.hpp"
#include "talus/vec3.hpp"

namespace talus::sph {

// Raw pointers to the neighbour set's fields (set B of a pass), in the type
// the store keeps them in: double, or float in a scene of mixed precision
// (then the terms read float and compute in double).
template <class Real>
struct NeighbourFields {
  const VectorOf<Real>* velocity = nullptr;
  const Real* density = nullptr;
  const Real* pressure = nullptr;
  const Real* sound_speed = nullptr;
  const Real* mass = nullptr;
  const std::int32_t* material = nullptr;
  const Real* inv_density = nullptr;    // 1/rho, refreshed with the density (saves divisions per pair)
  const double* viscosity = nullptr;    // mu_eff per particle, Pa s (non-Newtonian / turbulent passes only)
};
using Neighbours = NeighbourFields<double>;
using NeighboursF = NeighbourFields<float>;

// The neighbours of a pass in which every particle has one material and one
// mass (one fluid at one spacing, the usual scene): the terms then read
// neither per pair, which spares two of the nine loads a fluid pair makes.
// The values are the fields' own, and so are the results, bit for bit.
template <class Real>
struct UniformNeighbourFields : NeighbourFields<Real> {
  double mass_of_all = 0.0;
  std::int32_t material_of_all = 0;
};

// j's mass and material, as the terms read them.
template <class Real>
TALUS_PAIR_INLINE double mass_at(const NeighbourFields<Real>& nb, const Pair& q) {
  return nb.mass[q.j];
}
template <class Real>
TALUS_PAIR_INLINE double mass_at(const UniformNeighbourFields<Real>& nb, const Pair&) {
  return nb.mass_of_all;
}
template <class Real>
TALUS_PAIR_INLINE std::int32_t material_at(const NeighbourFields<Real>& nb, const Pair& q) {
  return nb.material[q.j];
}
template <class Real>
TALUS_PAIR_INLINE std::int32_t material_at(const UniformNeighbourFields<Real>& nb, const Pair&) {
  return nb.material_of_all;
}

// The neighbours of a pass of one material and one mass whose fields the
// mutual pass gathers from `record` (filled from the columns before the
// pass: neighbour_records.hpp), in double with v from its column, into each
// pair's Pair::j_state. The values are the columns', and so are the results,
// bit for bit.
template <class Real>
struct GatheredNeighbourFields : UniformNeighbourFields<Real> {
  const NeighbourRecordOf<Real>* record = nullptr;
};

// j's velocity, density, pressure, sound speed and 1/rho, as the terms read them.
template <class Real>
TALUS_PAIR_INLINE Vec3 velocity_at(const NeighbourFields<Real>& nb, const Pair& q) {
  return nb.velocity[q.j];
}
template <class Real>
TALUS_PAIR_INLINE double density_at(const NeighbourFields<Real>& nb, const Pair& q) {
  return nb.density[q.j];
}
template <class Real>
TALUS_PAIR_INLINE double pressure_at(const NeighbourFields<Real>& nb, const Pair& q) {
  return nb.pressure[q.j];
}
template <class Real>
TALUS_PAIR_INLINE double sound_speed_at(const NeighbourFields<Real>& nb, const Pair& q) {
  return nb.sound_speed[q.j];
}
template <class Real>
TALUS_PAIR_INLINE double inv_density_at(const NeighbourFields<Real>& nb, const Pair& q) {
  return nb.inv_density[q.j];
}
template <class Real>
TALUS_PAIR_INLINE Vec3 velocity_at(const GatheredNeighbourFields<Real>&, const Pair& q) { return q.j_state.v; }
template <class Real>
TALUS_PAIR_INLINE double density_at(const GatheredNeighbourFields<Real>&, const Pair& q) { return q.j_state.rho; }
template <class Real>
TALUS_PAIR_INLINE double pressure_at(const GatheredNeighbourFields<Real>&, const Pair& q) {
  return q.j_state.p;
}
template <class Real>
TALUS_PAIR_INLINE double sound_speed_at(const GatheredNeighbourFields<Real>&, const Pair& q) {
  return q.j_state.c;
}
template <class Real>
TALUS_PAIR_INLINE double inv_density_at(const GatheredNeighbourFields<Real>&, const Pair& q) {
  return q.j_state.inv_rho;
}

// Symmetric pressure force, momentum conserving (Monaghan 2005 eq. 3.6; rock-
// fluid seed eq. 14 in this form):  a_i += -sum_j m_j (p_i + p_j)/(rho_i rho_j) grad.
template <class NB = Neighbours>
struct PressureForce {
  static constexpr bool uses_value = false, uses_gradient = true;
  NB nb;
  template <class S>
  TALUS_PAIR_INLINE void pair(const Pair& q, S& s) const {
    const double f = mass_at(nb, q) * (s.p + pressure_at(nb, q)) * (s.inv_rho * inv_density_at(nb, q));
    s.acc -= q.grad() * f;
  }
  // grad_j W_ji = -grad_i W_ij: j gets +m_i times the shared factor.
  template <class S, class R>
  TALUS_PAIR_INLINE void mutual(const Pair& q, S& s, R& r) const {
    const Vec3 f = q.grad() * ((s.p + pressure_at(nb, q)) * (s.inv_rho * inv_density_at(nb, q)));
    s.acc -= f * mass_at(nb, q);
    r.acc += f * s.m;
  }
};

// Monaghan (1992) artificial viscosity, as in DualSPHysics:
//   Pi_ij = -alpha cbar_ij mu_ij / rhobar_ij  when v_ij . x_ij < 0,
//   mu_ij = h v_ij.x_ij / (r^2 + eta^2),  a_i += -sum_j m_j Pi_ij grad.
template <class NB = Neighbours>
struct ArtificialViscosity {
  static constexpr bool uses_value = false, uses_gradient = true;
  NB nb;
  double alpha_h = 0.0;  // alpha * h
  template <class S>
  TALUS_PAIR_INLINE void pair(const Pair& q, S& s) const {
    const double vdotx = dot(s.v - velocity_at(nb, q), q.dx);
    const double rate = vdotx * q.inv_r2e;
    s.visc = std::max(s.visc, std::abs(rate));
    // -m_j Pi_ij = m_j alpha h cbar rate / rhobar; cbar/rhobar = (c_i + c_j)/(rho_i + rho_j).
    // Zero for receding pairs, written without a branch: the sign of v.x is unpredictable.
    const double approaching = std::min(rate, 0.0);
    const double f = mass_at(nb, q) * alpha_h * approaching * (s.c + sound_speed_at(nb, q)) / (s.rho + density_at(nb, q));
    s.acc += q.grad() * f;
  }
  // v_ji . x_ji = v_ij . x_ij: the same Pi_ij, with the opposite gradient for j.
  template <class S, class R>
  TALUS_PAIR_INLINE void mutual(const Pair& q, S& s, R& r) const {
    const double rate = dot(s.v - velocity_at(nb, q), q.dx) * q.inv_r2e;
    const double speed = std::abs(rate);
    s.visc = std::max(s.visc, speed);
    const double approaching = std::min(rate, 0.0);
    const Vec3 f = q.grad() * (alpha_h * approaching * (s.c + sound_speed_at(nb, q)) / (s.rho + density_at(nb, q)));
    s.acc += f * mass_at(nb, q);
    r.acc -= f * s.m;
  }
};

// The regularisation eta^2 of the laminar operator below. The 0.01 h^2 of
// artificial viscosity (Pair::inv_r2e) weakens the nearest neighbours' share
// by ~2 % at h/dp = 1.5, which shows as a viscosity ~1.2 % low in Poiseuille
// flow; 1e-4 h^2 only guards against coincident particles.
inline double laminar_eta2(double h) { return 1e-4 * h * h; }

// (x_ij . grad W)/(r^2 + eta^2) with the laminar regularisation.
TALUS_PAIR_INLINE double laminar_weight(const Pair& q, double eta2) { return q.r2 * q.dw_r / (q.r2 + eta2); }

// Laminar viscosity, Morris et al. (1997) / Lo & Shao (2002) operator:
//   a_i += sum_j m_j (mu_i + mu_j)/(rho_i rho_j) (x_ij . grad)/(r^2 + eta^2) v_ij.
// `mu_of_material` gives mu_j by material; against walls (WallSide = true) the
// wall takes the fluid's viscosity, mu_j = mu_i (no-slip). eta2: laminar_eta2(h).
template <bool WallSide = false, class NB = Neighbours>
struct LaminarViscosity {
  static constexpr bool uses_value = false, uses_gradient = true;
  NB nb;
  const double* mu_of_material = nullptr;
  double eta2 = 0.0;
  template <class S>
  TALUS_PAIR_INLINE void pair(const Pair& q, S& s) const {
    const double mu_j = WallSide ? s.mu : mu_of_material[material_at(nb, q)];
    const Vec3 vij = s.v - velocity_at(nb, q);
    const double rate = dot(vij, q.dx) * q.inv_r2e;
    s.visc = std::max(s.visc, std::abs(rate));
    const double f = mass_at(nb, q) * (s.mu + mu_j) * (s.inv_rho * inv_density_at(nb, q)) * laminar_weight(q, eta2);
    s.acc += vij * f;
  }
  // Fluid pairs only: v_ji = -v_ij with the same weight.
  template <class S, class R>
  TALUS_PAIR_INLINE void mutual(const Pair& q, S& s, R& r) const {
    static_assert(!WallSide, "a wall set is not a fluid neighbour");
    const Vec3 vij = s.v - velocity_at(nb, q);
    const double speed = std::abs(dot(vij, q.dx) * q.inv_r2e);
    s.visc = std::max(s.visc, speed);
    const Vec3 f = vij * ((s.mu + mu_of_material[material_at(nb, q)]) * (s.inv_rho * inv_density_at(nb, q)) *
                          laminar_weight(q, eta2));
    s.acc += f * mass_at(nb, q);
    r.acc -= f * s.m;
  }
};

// How a pair's viscosity is formed from mu_eff of both particles.
//   arithmetic: mu_i + mu_j (Morris et al. 1997, J. Comput. Phys. 136, eq. 8)
//   harmonic:   4 mu_i mu_j / (mu_i + mu_j) (Cleary 1998, Appl. Math. Model. 22;
//               Shao & Lo 2003): continuous shear stress across a viscosity jump,
//               the better choice at a water-sediment interface.
enum class ViscosityMean { arithmetic, harmonic };

// Laminar viscosity of the three-pass non-Newtonian scheme (DESIGN.md): the
// Morris/Lo-Shao operator of LaminarViscosity with the per-particle apparent
// viscosity mu_eff (pass 2) of both particles; Sums carry mu = mu_eff[i].
template <ViscosityMean Mean, class NB = Neighbours>
struct LaminarViscosityField {
  static constexpr bool uses_value = false, uses_gradient = true;
  NB nb;  // nb.viscosity = mu_eff
  double eta2 = 0.0;  // laminar_eta2(h)
  template <class S>
  TALUS_PAIR_INLINE double pair_viscosity(const Pair& q, const S& s) const {
    const double mu_j = nb.viscosity[q.j];
    if constexpr (Mean == ViscosityMean::arithmetic)
      return s.mu + mu_j;
    else
      return s.mu + mu_j > 0.0 ? 4.0 * s.mu * mu_j / (s.mu + mu_j) : 0.0;
  }
  template <class S>
  TALUS_PAIR_INLINE void pair(const Pair& q, S& s) const {
    const double mu_pair = pair_viscosity(q, s);
    const Vec3 vij = s.v - velocity_at(nb, q);
    const double rate = dot(vij, q.dx) * q.inv_r2e;
    s.visc = std::max(s.visc, std::abs(rate));
    const double f = mass_at(nb, q) * mu_pair * (s.inv_rho * inv_density_at(nb, q)) * laminar_weight(q, eta2);
    s.acc += vij * f;
  }
  template <class S, class R>
  TALUS_PAIR_INLINE void mutual(const Pair& q, S& s, R& r) const {
    const double mu_pair = pair_viscosity(q, s);
    const Vec3 vij = s.v - velocity_at(nb, q);
    const double speed = std::abs(dot(vij, q.dx) * q.inv_r2e);
    s.visc = std::max(s.visc, speed);
    const Vec3 f = vij * (mu_pair * (s.inv_rho * inv_density_at(nb, q)) * laminar_weight(q, eta2));
    s.acc += f * mass_at(nb, q);
    r.acc -= f * s.m;
  }
};

// Pass 1 of the three-pass scheme: the velocity gradient with the kernel
// gradient correction of Bonet & Lok (1999, CMAME 180),
//   G_ab = sum_j V_j (v_j - v_i)_a dW_b,  L_ab = sum_j V_j (x_j - x_i)_a dW_b,
//   grad v = G L^-1   (exact for linear velocity fields, also in a truncated
//   support such as next to a wall without wall particles), V_j = m_j / rho_j.
// Sums carry `v` (v_i), `g[3][3]` and `l[3][3]`.
template <class NB = Neighbours>
struct VelocityGradient {
  static constexpr bool uses_value = false, uses_gradient = true;
  NB nb;
  template <class S>
  TALUS_PAIR_INLINE void pair(const Pair& q, S& s) const {
    const double vol = mass_at(nb, q) * inv_density_at(nb, q);
    const Vec3 dv = (velocity_at(nb, q) - s.v) * vol;
    const Vec3 dxj = q.dx * (-vol);  // V_j (x_j - x_i)
    const Vec3 gw = q.grad();
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) {
        s.g[a][b] += dv[a] * gw[b];
        s.l[a][b] += dxj[a] * gw[b];
      }
  }
};

// |D| = sqrt(2 D':D') from the sums of VelocityGradient: D the symmetric part
// of grad v, D' its deviator (the coastline seed's strain rate, §2.3.2). The
// correction L^-1 is used where L is well conditioned (det > 0.1: in the bulk
// and next to walls); at a thin free surface the raw gradient is kept.
inline double shear_rate_from_gradient(const double g[3][3], const double l[3][3], int dim) {
  double a[3][3] = {};
  double det = 0.0, inv[3][3] = {};
  if (dim == 2) {
    det = l[0][0] * l[1][1] - l[0][1] * l[1][0];
    if (det > 0.1) {
      inv[0][0] = l[1][1] / det;
      inv[0][1] = -l[0][1] / det;
      inv[1][0] = -l[1][0] / det;
      inv[1][1] = l[0][0] / det;
    }
  } else {
    det = l[0][0] * (l[1][1] * l[2][2] - l[1][2] * l[2][1]) - l[0][1] * (l[1][0] * l[2][2] - l[1][2] * l[2][0]) +
          l[0][2] * (l[1][0] * l[2][1] - l[1][1] * l[2][0]);
    if (det > 0.1) {
      inv[0][0] = (l[1][1] * l[2][2] - l[1][2] * l[2][1]) / det;
      inv[0][1] = (l[0][2] * l[2][1] - l[0][1] * l[2][2]) / det;
      inv[0][2] = (l[0][1] * l[1][2] - l[0][2] * l[1][1]) / det;
      inv[1][0] = (l[1][2] * l[2][0] - l[1][0] * l[2][2]) / det;
      inv[1][1] = (l[0][0] * l[2][2] - l[0][2] * l[2][0]) / det;
      inv[1][2] = (l[0][2] * l[1][0] - l[0][0] * l[1][2]) / det;
      inv[2][0] = (l[1][0] * l[2][1] - l[1][1] * l[2][0]) / det;
      inv[2][1] = (l[0][1] * l[2][0] - l[0][0] * l[2][1]) / det;
      inv[2][2] = (l[0][0] * l[1][1] - l[0][1] * l[1][0]) / det;
    }
  }
  if (det > 0.1) {
    for (int r = 0; r < dim; ++r)
      for (int c = 0; c < dim; ++c)
        for (int k = 0; k < dim; ++k) a[r][c] += g[r][k] * inv[k][c];
  } else {
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) a[r][c] = g[r][c];  // L ~ I in a full support: the raw gradient
  }
  const double tr = (a[0][0] + a[1][1] + a[2][2]) / 3.0;
  double dd = 0.0;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      const double d = 0.5 * (a[r][c] + a[c][r]) - (r == c ? tr : 0.0);
      dd += d * d;
    }
  return std::sqrt(2.0 * dd);
}

// Viscous force with the Müller viscosity-kernel Laplacian (rock-fluid seed
// eq. 18): a_i += mu_i/rho_i sum_j m_j (v_j - v_i)/rho_j lap W_ij.
// Needs a kernel with a Laplacian (the Müller set); the table's laplacian().
template <class NB = Neighbours>
struct LaplacianViscosity {
  static constexpr bool uses_value = false, uses_gradient = false;
  NB nb;
  const KernelTable* kernel = nullptr;
  const double* mu_of_material = nullptr;  // mu_j of a fluid neighbour (the mutual form)
  template <class S>
  TALUS_PAIR_INLINE void pair(const Pair& q, S& s) const {
    const double f = s.mu * s.inv_rho * mass_at(nb, q) * inv_density_at(nb, q) * kernel->laplacian(std::sqrt(q.r2));
    s.acc += (velocity_at(nb, q) - s.v) * f;
  }
  // Not symmetric in mu: j's share has mu_j / rho_j.
  template <class S, class R>
  TALUS_PAIR_INLINE void mutual(const Pair& q, S& s, R& r) const {
    const Vec3 vji = (velocity_at(nb, q) - s.v) * (s.inv_rho * inv_density_at(nb, q) * kernel->laplacian(std::sqrt(q.r2)));
    s.acc += vji * (s.mu * mass_at(nb, q));
    r.acc -= vji * (mu_of_material[material_at(nb, q)] * s.m);
  }
};

// Continuity equation in the form that holds across a density jump
// (Colagrossi & Landrini 2003, J. Comput. Phys. 191; as DualSPHysics'
// multiphase solver): drho_i/dt += rho_i sum_j (m_j/rho_j) v_ij . grad.
// With one density it equals Monaghan's sum_j m_j v_ij . grad to O(rho_i/rho_j - 1);
// at a water-sediment interface (1029 against 1922 kg/m^3) that form is wrong by
// the density ratio and the interface particles blow up. Sums carry `rho`.
template <class NB = Neighbours>
struct Continuity {
  static constexpr bool uses_value = false, uses_gradient = true;
  NB nb;  // needs inv_density
  template <class S>
  TALUS_PAIR_INLINE void pair(const Pair& q, S& s) const {
    s.drho += s.rho * mass_at(nb, q) * inv_density_at(nb, q) * dot(s.v - velocity_at(nb, q), q.grad());
  }
  // v_ji . grad_j W_ji = v_ij . grad_i W_ij: drho_j += rho_j (m_i/rho_i) times the same.
  template <class S, class R>
  TALUS_PAIR_INLINE void mutual(const Pair& q, S& s, R& r) const {
    const double vg = dot(s.v - velocity_at(nb, q), q.grad());
    s.drho += s.rho * mass_at(nb, q) * inv_density_at(nb, q) * vg;
    r.drho += density_at(nb, q) * s.m * s.inv_rho * vg;
  }
};

// delta-SPH density diffusion of Molteni & Colagrossi (2009), as in
// DualSPHysics (DDT 1):
//   drho_i/dt += delta h c0 sum_j 2 (rho_i - rho_j) (x_ij . grad)/(r^2 + eta^2) m_j/rho_j.
// Fourtakas et al. (2019, Comput. Fluids 190) subtract the hydrostatic part
// of the density difference, rho^H_i - rho^H_j = kbar g . x_ij with
// kbar = (rho_i/c_i^2 + rho_j/c_j^2)/2 (from dp = c^2 drho = rho g dz), so
// that a fluid at rest under gravity sees no diffusion at all.
// Only pairs of one material diffuse (Mokos et al. 2015, Comput. Part. Mech. 2,
// multiphase DualSPHysics): across an interface the density difference is the
// materials', not noise. Sums carry `mat`.
template <bool Hydrostatic, class NB = Neighbours>
struct DensityDiffusion {
  static constexpr bool uses_value = false, uses_gradient = true;
  NB nb;
  double delta_h_c0 = 0.0;  // delta * h * c0
  Vec3 gravity;
  // delta h c0 2 (rho_i - rho_j - hydrostatic part) (x_ij . grad)/(r^2 + eta^2).
  template <class S>
  TALUS_PAIR_INLINE double flux(const Pair& q, const S& s) const {
    const double same_material = s.mat == material_at(nb, q) ? 1.0 : 0.0;
    double drho = (s.rho - density_at(nb, q)) * same_material;
    if constexpr (Hydrostatic) {
      // rho_j/c_j^2 from the two fields the pair loads anyway: a division
      // costs no more than loading a third.
      const double c_j = sound_speed_at(nb, q);
      const double kbar = 0.5 * (s.kh + density_at(nb, q) / (c_j * c_j));
      drho -= kbar * dot(gravity, q.dx) * same_material;
    }
    return delta_h_c0 * 2.0 * drho * (q.r2 * q.dw_r) * q.inv_r2e;
  }
  template <class S>
  TALUS_PAIR_INLINE void pair(const Pair& q, S& s) const {
    s.drho += flux(q, s) * mass_at(nb, q) * inv_density_at(nb, q);
  }
  // The difference and x_ij change sign for j: drho_j -= the flux times m_i/rho_i.
  template <class S, class R>
  TALUS_PAIR_INLINE void mutual(const Pair& q, S& s, R& r) const {
    const double f = flux(q, s);
    s.drho += f * mass_at(nb, q) * inv_density_at(nb, q);
    r.drho -= f * s.m * s.inv_rho;
  }
};

// Summation density (rock-fluid seed eq. 12): rho_i = sum_j m_j W_ij; the
// pass's Sums carry `rho_sum`.
template <class Real = double>
struct DensitySum {
  static constexpr bool uses_value = true, uses_gradient = false;
  const Real* mass = nullptr;
  template <class S>
  TALUS_PAIR_INLINE void pair(const Pair& q, S& s) const {
    s.rho_sum += mass[q.j] * q.w;
  }
};

// The sums of a summation-density pass (DensitySum's accumulator).
struct DensitySums {
  double rho_sum = 0.0;
};

// Shepard-weighted hydrostatic extrapolation of the fluid pressure to a wall
// or block particle b (Adami et al. 2012, eq. 27):
//   p_b = sum_f W_bf (p_f + rho_f g . (x_b - x_f)) / sum_f W_bf.
// Run as a pass over wall particles (i = b) against the fluid (j = f).
struct ExtrapolationSums {
  double wsum = 0.0, psum = 0.0;
};
template <class Real = double>
struct PressureExtrapolation {
  static constexpr bool uses_value = true, uses_gradient = false;
  const Real* p;
  const Real* rho;
  Vec3 g;
  TALUS_PAIR_INLINE void pair(const Pair& q, ExtrapolationSums& s) const {
    // dx = x_i - x_j = x_b - x_f: the hydrostatic step from fluid particle f to wall particle b.
    s.wsum += q.w;
    s.psum += q.w * (p[q.j] + rho[q.j] * dot(g, q.dx));
  }
};

}  // namespace talus::sph
