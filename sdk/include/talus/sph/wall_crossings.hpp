// What a wall model does with a fluid particle it finds inside its wall
// (SphBoundary::hold_fluid): puts it back on the wall surface, takes away
// its velocity into the wall, counts it once in World::wall_crossings and
// warns the first one of each wall with where and when.
#pragma once

#include <cstdint>
#include <string>
#include <unordered_set>
#include <vector>

#include "talus/number_text.hpp"
#include "talus/periodic.hpp"
#include "talus/world.hpp"

namespace talus::sph {

class WallCrossings {
 public:
  // Fluid particle i is inside wall `wall` (named `what`, e.g. "wall 'tank'"):
  // it goes to `surface`, the nearest point of the wall surface, where the
  // wall moves at `wall_velocity` and `normal` points out of the wall.
  // Returns the particle's change of momentum (a movable wall takes minus it).
  Vec3 put_back(World& world, std::size_t i, const Vec3& surface, const Vec3& normal, const Vec3& wall_velocity,
                std::size_t wall, const std::string& what, double time) {
    auto x = world.fluid.position();
    const Vec3 was = x[i];
    x[i] = wrap_periodic(world, surface);
    Vec3 change;
    // Velocity and mass in the type they are kept in (float under mixed precision).
    world.fluid.visit_vector("velocity", [&](auto v) {
      const double into = dot(Vec3(v[i]) - wall_velocity, normal);
      if (into >= 0.0) return;
      v[i] = Vec3(v[i]) - normal * into;
      world.fluid.visit_scalar("mass", [&](auto m) { change = normal * (-into * m[i]); });
    });
    record(world, i, was, wall, what, time,
           "was put back on its surface (more wall layers, a smaller time step or \"method\": \"mdbc\" hold the "
           "fluid better)");
    return change;
  }

  // Fluid particle i is inside `what` where no wall particles stop it: counted and warned, left where it is.
  void count(World& world, std::size_t i, std::size_t wall, const std::string& what, double time) {
    record(world, i, world.fluid.position()[i], wall, what, time, "was left there");
  }

 private:
  void record(World& world, std::size_t i, const Vec3& at, std::size_t wall, const std::string& what, double time,
              const std::string& done) {
    const std::uint64_t id = world.fluid.ids()[i];
    if (!crossed_.insert(id).second) return;
    ++world.wall_crossings;
    if (warned_.size() <= wall) warned_.resize(wall + 1, 0);
    if (warned_[wall]) return;
    warned_[wall] = 1;
    world.warnings.add("t = " + fixed(time, 6) + " s: fluid particle " + std::to_string(id) + " was inside " + what +
                       " at " + vec_text(at, world.dim) + " and " + done +
                       "; the summary counts every such particle");
  }


  std::unordered_set<std::uint64_t> crossed_;  // fluid ids already counted
  std::vector<char> warned_;                   // per wall
};

}  // namespace talus::sph
