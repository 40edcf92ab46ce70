// What every fluid-block boundary model shares: finding its blocks in
// world.blocks (which the dda stage creates at its setup, so the dda stage
// must come before the fluid stage), clearing fluid from inside the blocks at
// the start, and handing the fluid's force to the blocks exactly once per step.
#pragma once

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "talus/periodic.hpp"
#include "talus/vec3.hpp"

namespace talus::coupling {

// Periodic axes: talus/periodic.hpp (the dda stage does not wrap blocks, so a
// block may straddle a periodic boundary and the passes use minimum images).

// Index in world.blocks of each body; throws InputError naming /pipeline when
// the dda stage has not set up yet (it must be listed before the fluid stage).
std::vector<std::size_t> find_blocks(const World& world, std::span<const int> bodies, const std::string& model);

// Removes fluid particles closer than `clearance` to (or inside) the blocks;
// returns how many.
std::size_t clear_fluid_inside(World& world, std::span<const std::size_t> blocks, double clearance);

// The only fluid material of the scene, or the one named; throws otherwise.
int coupling_material(const World& world, int body, const std::string& model, const std::string& name);

// Hands the fluid's force to the DDA blocks with action = reaction exactly.
//
// The wcsph stage evaluates its rates one or more times per host step; the
// fluid's momentum changes by dt times the rates of the last evaluation
// (Euler: at t^n; symplectic and predictor-corrector: at t^n+1/2). The wall
// model calls set() after every evaluation and commit() from every
// advance_walls(); the last commit of a step is the one that counts. The dda
// stage runs before the fluid stage, so what the fluid gave in step n reaches
// the blocks in step n+1, as external_force held constant over the DDA's
// sub-steps (the dda stage applies and clears it). The impulse owed is kept
// exactly: impulse given by the fluid minus impulse delivered (external force
// x host dt), so a change of dt between steps is made good in the next step.
class ImpulseLedger {
 public:
  void reset(std::size_t blocks);
  // Start of the fluid step: the dda stage has applied what was committed.
  void begin_step();
  // The force and torque (about the centroid) this rank's own fluid exerts
  // on block k at the last evaluation (on one rank: all the fluid).
  void set(std::size_t k, const Vec3& force, const Vec3& torque) {
    share_[6 * k + 0] = force.x, share_[6 * k + 1] = force.y, share_[6 * k + 2] = force.z;
    share_[6 * k + 3] = torque.x, share_[6 * k + 4] = torque.y, share_[6 * k + 5] = torque.z;
  }
  // Fluid state advanced to `time` with rates applied over `dt`. On several
  // MPI ranks every rank calls it: the forces are summed over the ranks, so
  // every rank's blocks get the same.
  void commit(World& world, std::span<const std::size_t> blocks, double time, double dt);
  // Impulses (and their moments about the centroid) this rank's fluid gave
  // the blocks outside its rates, after the step's last commit (fluid
  // particles stopped at a block's face), per block: owed, and delivered over
  // the next step. Every rank calls it (the impulses are summed over the ranks).
  void add_impulses(World& world, std::span<const std::size_t> blocks, std::span<const Vec3> impulse,
                    std::span<const Vec3> angular, double time);

  const Vec3& force(std::size_t k) const { return force_[k]; }
  const Vec3& torque(std::size_t k) const { return torque_[k]; }
  // Impulse given by the fluid that the blocks have not received yet.
  const Vec3& owed(std::size_t k) const { return owed_[k]; }
  // Total impulse the fluid has given to block k since the start.
  const Vec3& given(std::size_t k) const { return given_[k]; }

  // What carries over from one step to the next (owed, given, committed and
  // the last evaluation's force), for checkpoints; the same bits on every
  // rank. load_state throws InputError when the bytes are not a ledger of
  // this many blocks.
  std::string save_state() const;
  void load_state(std::string_view bytes, const char* what);

 private:
  std::vector<double> share_;                           // this rank's force and torque per block, last evaluation
  std::vector<double> sums_;                            // scratch for the sums over the ranks
  std::vector<Vec3> force_, torque_;                    // last evaluation, all ranks
  std::vector<Vec3> owed_, owed_angular_;               // after the last commit
  std::vector<Vec3> owed_start_, owed_angular_start_;   // at begin_step
  std::vector<Vec3> given_, given_start_;
  std::vector<Vec3> committed_, committed_torque_;      // in external_force now
  std::vector<Vec3> applied_, applied_torque_;          // what the dda stage applied this step
};

}  // namespace talus::coupling
