// Narrow phase for two convex polyhedra: separating-axis test over the face
// normals of both blocks and the edge-edge axes that are faces of their
// Minkowski difference (Gauss-map test, Gregorius 2013 "The Separating Axis
// Test between Convex Polyhedra"), then a contact manifold:
//   - face axis: the incident face of the other block is clipped against the
//     side planes of the reference face (Sutherland-Hodgman); every clipped
//     point within the margin is a contact point. Covers face-face,
//     edge-face and vertex-face contacts, coplanar faces and resting contact.
//   - edge axis: one point, the midpoint of the closest points of the edges.
// Face axes are preferred over edge axes, and block a's faces over b's,
// unless the other is better by a tolerance, so that a resting contact keeps
// its reference face (and its feature ids, hence its spring history).
#pragma once

#include <cstdint>
#include <vector>

#include "talus/blocks.hpp"
#include "talus/vec3.hpp"

namespace talus::dda {

// A block's geometry in the world frame for this step.
struct PosedBlock {
  const Polyhedron* shape = nullptr;
  const Vec3* vertices = nullptr;  // world positions, shape->vertices.size()
  const Vec3* normals = nullptr;   // world face normals
  const double* offsets = nullptr; // world face plane offsets
  Vec3 centre{};
};

struct ContactPoint {
  Vec3 point{};       // midway between the two surfaces
  Vec3 normal{};      // unit, from a to b
  double gap = 0.0;   // < 0: penetration
  double area = 0.0;  // tributary area of a face-face contact point, else 0
  std::uint64_t feature = 0;  // identifies the point within the pair from step to step
  int manifold_size = 1;
};

// Feature kinds (top bits of ContactPoint::feature).
inline constexpr std::uint64_t feature_face_a = 1ull << 62;  // reference face on a
inline constexpr std::uint64_t feature_face_b = 2ull << 62;  // reference face on b
inline constexpr std::uint64_t feature_edges = 3ull << 62;

struct NarrowPhaseScratch {
  struct EdgeData {
    Vec3 c, d, d_x_c;  // negated normals of the two faces at the edge, and their cross product
    Vec3 point, direction;
  };
  std::vector<EdgeData> edges;
  std::vector<ContactPoint> points;
  std::vector<Vec3> poly, next;
  std::vector<std::uint64_t> ids, next_ids;
};

// Appends the contact points of a and b (if their gap is below `margin`) to
// `out`; returns how many.
int collide(const PosedBlock& a, const PosedBlock& b, double margin, std::vector<ContactPoint>& out,
            NarrowPhaseScratch& scratch);

// Separation along the best separating axis (negative: penetration depth),
// without building a manifold.
double separation(const PosedBlock& a, const PosedBlock& b);

}  // namespace talus::dda
