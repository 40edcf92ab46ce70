// Penalty "repulsion" walls of the rock-fluid seed (§4, eq. 22): a fluid
// particle closer to a wall surface than the activation distance r0 feels the
// penalty spring of sph/penalty.hpp with d = r0 - (distance to the surface),
// n the unit normal pointing into the fluid and v the particle velocity
// relative to the (fixed) wall. No wall particles: the walls are planes
// (half_space, the closed faces of box_walls) or closed triangle meshes.
// The spring bounds the time step (PenaltySpring::stable_time_step).
#pragma once

#include <vector>

#include "talus/mesh.hpp"
#include "talus/sph/boundary_pass.hpp"
#include "talus/sph/penalty.hpp"

namespace talus::boundary {

class Repulsion final : public sph::SphBoundary {
 public:
  static ParamSet describe();
  explicit Repulsion(const ParamValues& v);

  void setup(World& world, std::span<const int> bodies) override;
  // No wall particles: the forces need only each fluid particle's own place.
  std::string why_not_on_ranks() const override { return {}; }
  void bind(World& world, const sph::FluidSettings& settings) override;
  void begin_step(World&) override {}
  std::uint64_t add_direct_forces(World& world, const sph::FluidView& fluid, const sph::FluidRates& rates) override;
  void advance_walls(World&, double, double) override {}
  double stable_time_step(const World& world) const override;
  void describe_passes(StagePlan& plan) const override;

  struct Plane {
    Vec3 point, normal;  // normal into the fluid, unit
    double r0;
  };
  struct Mesh {
    TriangleMesh mesh;
    Vec3 lo, hi;  // bounds grown by r0
    double r0;
  };
  const std::vector<Plane>& planes() const { return planes_; }

 private:
  sph::PenaltySpring spring_;
  bool has_distance_;
  double distance_;
  std::vector<Plane> planes_;
  std::vector<Mesh> meshes_;
  std::vector<std::string> body_names_;
  double min_mass_ = 0.0;
};

}  // namespace talus::boundary
