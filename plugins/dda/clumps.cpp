// Clumps: blocks that share a scene "clump" name move as one rigid body, a
// non-convex block made of convex pieces (a landslide mass cut into columns,
// a boulder of several polyhedra). The body's centroid, mass and inertia are
// the pieces' (parallel axes); contacts between its pieces are not sought.
#include <cmath>
#include <map>
#include <string>

#include "dda_stage.hpp"
#include "rigid_motion.hpp"
#include "talus/world.hpp"

namespace talus::dda {

void DdaStage::build_clumps(const World& world, BlockSet& b) {
  const std::size_t n = b.size();
  lead_.resize(n);
  offset_.assign(n, {});
  body_radius_.resize(n);
  body_mass_.assign(b.mass.begin(), b.mass.end());
  std::map<std::string, std::uint32_t> first;
  for (std::size_t i = 0; i < n; ++i) {
    lead_[i] = static_cast<std::uint32_t>(i);
    body_radius_[i] = b.shape[i].radius;
    const ParamValues& p = world.bodies[b.body[i]].params;
    if (!p.has("clump")) continue;
    if (!dynamic_[i])
      p.fail("clump", "block '" + b.name[i] + "' is " + (b.fixed[i] ? "fixed" : "moved by its motion") +
                          "; a clump is a free body (its blocks move by forces only)");
    const auto [it, inserted] = first.emplace(p.string("clump"), static_cast<std::uint32_t>(i));
    lead_[i] = it->second;
    if (!inserted && (norm2(b.velocity[i] - b.velocity[it->second]) > 0.0 ||
                      norm2(b.angular_velocity[i] - b.angular_velocity[it->second]) > 0.0))
      p.fail("clump", "block '" + b.name[i] + "' starts with another velocity than block '" + b.name[it->second] +
                          "' of its clump '" + it->first + "'; a clump moves as one body");
  }
  member_begin_.assign(n + 1, 0);
  for (std::size_t i = 0; i < n; ++i) ++member_begin_[lead_[i] + 1];
  for (std::size_t i = 0; i < n; ++i) member_begin_[i + 1] += member_begin_[i];
  members_.resize(n);
  std::vector<std::uint32_t> fill(member_begin_.begin(), member_begin_.end() - 1);
  for (std::size_t i = 0; i < n; ++i) members_[fill[lead_[i]]++] = static_cast<std::uint32_t>(i);

  for (const auto& [name, l] : first) {
    const std::uint32_t* begin = members_.data() + member_begin_[l];
    const std::uint32_t* end = members_.data() + member_begin_[l + 1];
    if (end - begin < 2) continue;
    double mass = 0.0;
    Vec3 centroid{};
    for (const std::uint32_t* m = begin; m != end; ++m) {
      mass += b.mass[*m];
      centroid += b.mass[*m] * b.position[*m];
    }
    centroid = centroid / mass;
    // Inertia about the body's centroid (orientations are the identity at the
    // start, so the body frame is the world frame), and the farthest point.
    std::array<double, 9> inertia{};
    double radius = 0.0;
    for (const std::uint32_t* m = begin; m != end; ++m) {
      const Vec3 r = b.position[*m] - centroid;
      offset_[*m] = r;
      const double r2 = norm2(r);
      for (int a = 0; a < 3; ++a)
        for (int c = 0; c < 3; ++c)
          inertia[3 * a + c] += b.inertia[*m][3 * a + c] + b.mass[*m] * ((a == c ? r2 : 0.0) - r[a] * r[c]);
      radius = std::max(radius, std::sqrt(r2) + b.shape[*m].radius);
      inverse_mass_[*m] = 0.0;
      agility_[*m] = 0.0;
      momentum_[*m] = {};
    }
    inverse_mass_[l] = 1.0 / mass;
    inverse_inertia_[l] = inverse(inertia);
    agility_[l] = 1.0 / mass + radius * radius / smallest_eigenvalue(inertia);
    body_radius_[l] = radius;
    body_mass_[l] = mass;
    // The lead's velocity is the body's; each piece moves with the body's
    // rotation about the centroid.
    const Vec3 v = b.velocity[l], w = b.angular_velocity[l];
    momentum_[l] = multiply(inertia, w);
    for (const std::uint32_t* m = begin; m != end; ++m)
      b.velocity[*m] = v + cross(w, offset_[*m]);
  }
}

}  // namespace talus::dda
