// mDBC ghost-node extrapolation (sph/ghost_nodes.hpp): one pass of the ghost
// nodes over the fluid gathers the moment matrix and the right-hand sides,
// and a fixed-size LU per wall particle solves it.
#include "talus/sph/ghost_nodes.hpp"

#include <Eigen/Dense>
#include <cmath>

#include "talus/error.hpp"
#include "talus/sph/pair_loop.hpp"

namespace talus::sph {

namespace {

using Matrix4 = Eigen::Matrix4d;

// Row r holds test function t_r = (W, dW/dx, dW/dy, dW/dz) of the ghost node.
struct MomentSums {
  Matrix4 a = Matrix4::Zero();    // sum V_j t_r u_c, u = (1, x_j - x_g)
  Matrix4 rhs = Matrix4::Zero();  // columns: sum V_j p_j t_r, then sum V_j v_j[k] t_r
};

// NB: the fluid's NeighbourFields, in double or float; the sums in double.
template <class NB>
struct MomentTerm {
  static constexpr bool uses_value = true, uses_gradient = true;
  NB fluid;
  template <class S>
  void pair(const Pair& q, S& s) const {
    const double vol = static_cast<double>(fluid.mass[q.j]) * fluid.inv_density[q.j];
    const Vec3 g = q.grad();
    const Eigen::Vector4d t{q.w, g.x, g.y, g.z};
    const Eigen::Vector4d u{1.0, -q.dx.x, -q.dx.y, -q.dx.z};  // dx = x_g - x_j
    const Vec3 v = fluid.velocity[q.j];
    const double pressure = fluid.pressure[q.j];
    s.a.noalias() += (vol * t) * u.transpose();
    s.rhs.col(0) += (vol * pressure) * t;
    s.rhs.col(1) += (vol * v.x) * t;
    s.rhs.col(2) += (vol * v.y) * t;
    s.rhs.col(3) += (vol * v.z) * t;
  }
};

}  // namespace

std::uint64_t extrapolate_from_ghost_nodes(int dim, const GhostNodes& nodes, const FluidView& fluid,
                                           const KernelTable& kernel, WallSlip slip, std::span<double> pressure,
                                           std::span<Vec3> viscous_velocity) {
  const std::size_t n = nodes.wall.size();
  if (nodes.ghost.size() != n || nodes.velocity.size() != n || pressure.size() != n ||
      !(viscous_velocity.empty() || viscous_velocity.size() == n))
    throw RunError("extrapolate_from_ghost_nodes: the wall spans differ in length");
  if (fluid.in_single() ? !fluid.single.inv_density : fluid.inv_density.size() != fluid.mass.size())
    throw RunError("extrapolate_from_ghost_nodes: no 1/rho of the fluid");
  const int size = dim + 1;  // unknowns: the value and its gradient in the domain's axes
  const bool velocity_wanted = !viscous_velocity.empty();

  auto start = [](Index) { return MomentSums{}; };
  auto finish = [&](Index b, const MomentSums& s) {
    const Vec3& wall_v = nodes.velocity[b];
    const Vec3 to_wall = nodes.wall[b] - nodes.ghost[b];
    double p = 0.0;
    Vec3 ghost_v = wall_v;  // no fluid in reach: nothing to mirror
    Matrix4 a = Matrix4::Identity();  // the unused axis (2D) stays the identity
    a.topLeftCorner(size, size) = s.a.topLeftCorner(size, size);
    if (std::abs(a.determinant()) >= ghost_determinant_limit) {
      Matrix4 rhs = s.rhs;
      rhs.bottomRows(4 - size).setZero();
      const Matrix4 x = a.partialPivLu().solve(rhs);
      p = x(0, 0) + to_wall.x * x(1, 0) + to_wall.y * x(2, 0) + (dim == 3 ? to_wall.z * x(3, 0) : 0.0);
      ghost_v = {x(0, 1), x(0, 2), x(0, 3)};
    } else if (s.a(0, 0) > 0.0) {  // Shepard
      p = s.rhs(0, 0) / s.a(0, 0);
      ghost_v = Vec3{s.rhs(0, 1), s.rhs(0, 2), s.rhs(0, 3)} * (1.0 / s.a(0, 0));
    }
    pressure[b] = p;
    if (!velocity_wanted) return;
    if (slip == WallSlip::no_slip) {
      viscous_velocity[b] = wall_v * 2.0 - ghost_v;
    } else {
      const Vec3 normal = to_wall * (-1.0 / norm(to_wall));
      viscous_velocity[b] = ghost_v + normal * (2.0 * dot(wall_v - ghost_v, normal));
    }
  };
  return fluid.visit_neighbours([&](const auto& fields) {
    return pair_pass(n, nodes.ghost, *fluid.cells, kernel, other_set, start, finish, MomentTerm{fields});
  });
}

}  // namespace talus::sph
