// Rigid blocks (explicit 3D DDA) as structure-of-arrays: one entry per block.
// The DDA stage owns the integration; coupling stages read poses and add
// external forces here, which the DDA stage applies and clears each step.
//
// A body-frame point p of block i is at position[i] + rotate(orientation[i], p)
// in the world (BlockSet::to_world); its velocity is velocity[i] +
// angular_velocity[i] x (x - position[i]) (BlockSet::velocity_at).
#pragma once

#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "talus/config.hpp"
#include "talus/vec3.hpp"

namespace talus {

// Unit quaternion (w, x, y, z) rotating body-frame vectors to the world frame.
struct Quaternion {
  double w = 1.0, x = 0.0, y = 0.0, z = 0.0;
};

inline Quaternion operator*(const Quaternion& a, const Quaternion& b) {
  return {a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z, a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y,
          a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x, a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w};
}

inline Quaternion conjugate(const Quaternion& q) { return {q.w, -q.x, -q.y, -q.z}; }

inline Quaternion normalised(const Quaternion& q) {
  const double n = std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
  return {q.w / n, q.x / n, q.y / n, q.z / n};
}

// q v q*, without building the matrix.
inline Vec3 rotate(const Quaternion& q, const Vec3& v) {
  const Vec3 u{q.x, q.y, q.z};
  const Vec3 t = 2.0 * cross(u, v);
  return v + q.w * t + cross(u, t);
}

inline Vec3 rotate_inverse(const Quaternion& q, const Vec3& v) { return rotate(conjugate(q), v); }

// The exact rotation by the rotation vector r (angle |r| about r/|r|).
inline Quaternion from_rotation_vector(const Vec3& r) {
  const double angle = norm(r);
  // sin(a/2)/a by its series near 0 so that tiny rotations stay exact.
  const double s = angle < 1e-8 ? 0.5 - angle * angle / 48.0 : std::sin(0.5 * angle) / angle;
  return {std::cos(0.5 * angle), s * r.x, s * r.y, s * r.z};
}

// Row-major rotation matrix of q.
inline std::array<double, 9> rotation_matrix(const Quaternion& q) {
  const double w = q.w, x = q.x, y = q.y, z = q.z;
  return {1 - 2 * (y * y + z * z), 2 * (x * y - w * z),     2 * (x * z + w * y),
          2 * (x * y + w * z),     1 - 2 * (x * x + z * z), 2 * (y * z - w * x),
          2 * (x * z - w * y),     2 * (y * z + w * x),     1 - 2 * (x * x + y * y)};
}

// A convex polyhedron in its body frame (centroid at the origin). Faces are
// counter-clockwise seen from outside. The derived members are filled by
// talus::dda::make_convex_polyhedron (talus/dda/polyhedron.hpp), which also
// merges coplanar faces into one polygon.
struct Polyhedron {
  struct Edge {
    int v0 = 0, v1 = 0;  // vertices; v0 -> v1 runs counter-clockwise around face f0
    int f0 = 0, f1 = 0;  // the two faces that share the edge
  };

  std::vector<Vec3> vertices;
  std::vector<std::vector<int>> faces;

  std::vector<Vec3> normals;    // unit outward normal of each face
  std::vector<double> offsets;  // face plane: dot(normal, x) = offset
  std::vector<Edge> edges;      // each edge once
  double radius = 0.0;          // largest distance of a vertex from the centroid, m
};

// Energies of the block system (J), updated by the DDA stage every step.
// Conservation check: kinetic + potential + strain + dissipated - external_work
// stays at its initial value (up to the time-integration error).
struct BlockEnergy {
  double kinetic = 0.0;        // translational + rotational
  double potential = 0.0;      // -sum m g.x of the free blocks
  double strain = 0.0;         // elastic energy in the contact springs
  double dissipated = 0.0;     // friction slip + contact damping, accumulated since t = 0
  double external_work = 0.0;  // work of external_force/torque and prescribed motions, accumulated
};

class TALUS_API BlockSet {
 public:
  ~BlockSet();

  std::size_t size() const { return name.size(); }

  // World position of a body-frame point of block i.
  Vec3 to_world(std::size_t i, const Vec3& body_point) const {
    return position[i] + rotate(orientation[i], body_point);
  }
  // Velocity of the material point of block i now at world position x.
  Vec3 velocity_at(std::size_t i, const Vec3& x) const {
    return velocity[i] + cross(angular_velocity[i], x - position[i]);
  }

  std::vector<std::string> name;
  std::vector<int> body;                    // index of the scene body
  std::vector<bool> fixed;                  // bedrock, walls: never move
  std::vector<bool> kinematic;              // moved by a prescribed motion, not by forces
  std::vector<double> mass;                 // kg
  std::vector<double> volume;               // m^3
  std::vector<std::array<double, 9>> inertia;  // body-frame inertia tensor about the centroid, kg m^2, row major
  std::vector<Polyhedron> shape;            // body frame

  std::vector<Vec3> position;               // centroid, world frame, m
  std::vector<Quaternion> orientation;
  std::vector<Vec3> velocity;               // m/s
  std::vector<Vec3> angular_velocity;       // world frame, rad/s
  std::vector<Vec3> bounds_lo, bounds_hi;   // world-frame bounding box of each block, refreshed every step

  std::vector<Vec3> external_force;         // N, summed by coupling stages this step
  std::vector<Vec3> external_torque;        // N m about the centroid

  BlockEnergy energy;
};

}  // namespace talus
