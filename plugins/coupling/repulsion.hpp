// `block_repulsion`: penalty repulsion between fluid particles and a DDA block's faces
// (rock-fluid seed §4, eq. 22): the penalty spring of sph/penalty.hpp on a
// fluid particle, with d = r0 - s the penetration into a layer of thickness r0
// outside the block (s: signed distance to the nearest face plane, the
// largest of the face-plane distances, so a particle inside the block is
// pushed out through its nearest face), n that face's outward normal and v
// the particle's velocity relative to the block's surface.
// Reaction: the block gets -F at the particle, summed once per step
// (block_link.hpp).
#pragma once

#include <vector>

#include "block_link.hpp"
#include "talus/sph/boundary_pass.hpp"
#include "talus/sph/penalty.hpp"

namespace talus::coupling {

class Repulsion final : public sph::SphBoundary {
 public:
  static ParamSet describe();
  explicit Repulsion(const ParamValues& v);

  void setup(World& world, std::span<const int> bodies) override;
  std::string why_not_on_ranks() const override;
  void bind(World& world, const sph::FluidSettings& settings) override;
  void begin_step(World&) override { ledger_.begin_step(); }
  std::uint64_t add_direct_forces(World& world, const sph::FluidView& fluid, const sph::FluidRates& rates) override;
  void advance_walls(World& world, double time, double dt) override { ledger_.commit(world, blocks_, time, dt); }
  double stable_time_step(const World& world) const override;
  void describe_passes(StagePlan& plan) const override;
  std::string save_state() const override { return ledger_.save_state(); }
  void load_state(std::string_view bytes) override { ledger_.load_state(bytes, "the repulsion model's impulse ledger"); }

  std::size_t blocks() const { return blocks_.size(); }
  std::size_t block_index(std::size_t k) const { return blocks_[k]; }
  const ImpulseLedger& ledger() const { return ledger_; }
  double stiffness() const { return spring_.stiffness; }
  double damping() const { return spring_.damping; }
  double distance() const { return r0_; }

 private:
  double ks_param_ = 0.0, kd_param_ = -1.0, r0_param_ = 0.0;
  std::string material_name_;
  sph::PenaltySpring spring_;
  double r0_ = 0.0, min_mass_ = 0.0;
  std::vector<int> bodies_;
  std::vector<std::string> names_;
  std::vector<std::size_t> blocks_;
  std::vector<Vec3> normals_;    // world-frame face normals of the current block
  std::vector<double> offsets_;
  Vec3 period_{};  // domain length on periodic axes: fluid is taken at its image nearest the block
  std::vector<Vec3> thread_force_, thread_torque_;
  ImpulseLedger ledger_;
};

}  // namespace talus::coupling
