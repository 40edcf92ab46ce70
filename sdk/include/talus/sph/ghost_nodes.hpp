// The modified dynamic boundary condition (mDBC; English, Domínguez,
// Vacondio, Crespo, Stansby, Lind, Chiapponi & Gómez-Gesteira 2022, Comput.
// Part. Mech. 9, 1-15, as DualSPHysics implements it). Each wall particle b
// has a ghost node g mirrored across the wall surface into the fluid,
// x_g = 2 s_b - x_b with s_b the surface point nearest b. A fluid field f and
// its gradient at g come from the first-order consistent interpolation
// (Liu & Liu 2006), the (dim+1) x (dim+1) system over the fluid neighbours j
// of g, V_j = m_j / rho_j:
//   [ sum V_j W_gj       sum V_j (x_j - x_g)^T W_gj       ] [ f_g      ]   [ sum V_j f_j W_gj      ]
//   [ sum V_j grad W_gj  sum V_j grad W_gj (x_j - x_g)^T  ] [ grad f_g ] = [ sum V_j f_j grad W_gj ]
// and the wall particle takes f_b = f_g + (x_b - x_g) . grad f_g: a field that
// varies linearly (the hydrostatic pressure) is continued exactly behind the
// wall. Where the system is close to singular (|det| < 1e-3, the determinant
// is dimensionless: a ghost with few fluid neighbours) the Shepard value
// f_g = sum V_j f_j W / sum V_j W is used, without gradient.
//
// The field extrapolated is the pressure, where English et al. extrapolate
// the density: the model turns it into the wall density with the wall
// material's EOS (never below rho0). For one fluid with a linear EOS the two
// are the same; next to fluids of different reference densities (water over
// a sediment bed) only the pressure is continuous, and a wall given the
// sediment's density with the water's EOS would push with megapascals.
// With no fluid in reach the pressure is zero.
//
// The velocity the viscous term sees at b mirrors the fluid velocity at the
// ghost node v_g (the zeroth-order part of the same system) about the wall's
// own velocity v_w:
//   no_slip:   v_b = 2 v_w - v_g                         (v = v_w on the surface)
//   free_slip: v_b = v_g + 2 ((v_w - v_g) . n) n          (normal part mirrored:
//              no flow through the wall; tangential part the fluid's: no shear)
// with n = (x_g - x_b) / |x_g - x_b| the wall normal into the fluid.
#pragma once

#include <cstdint>
#include <span>

#include "talus/config.hpp"
#include "talus/kernel_table.hpp"
#include "talus/sph/boundary_pass.hpp"
#include "talus/vec3.hpp"

namespace talus::sph {

enum class WallSlip { no_slip, free_slip };

// The wall particles of one extrapolation: positions, ghost nodes, the walls' own velocity.
struct GhostNodes {
  std::span<const Vec3> wall, ghost, velocity;
};

// Fills pressure[b] for every wall particle and, when viscous_velocity is not
// empty, the velocity the viscous term sees; returns the pair evaluations.
TALUS_API std::uint64_t extrapolate_from_ghost_nodes(int dim, const GhostNodes& nodes, const FluidView& fluid,
                                                     const KernelTable& kernel, WallSlip slip,
                                                     std::span<double> pressure, std::span<Vec3> viscous_velocity);

// The determinant below which a ghost node falls back to the Shepard value.
inline constexpr double ghost_determinant_limit = 1e-3;

}  // namespace talus::sph
