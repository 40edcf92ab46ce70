// The `dda` stage: explicit 3D discontinuous deformation analysis of rigid
// polyhedral blocks (seed sph-dda-rock-fluid-3d §2; Shi 1988; explicit
// variant of Mikola & Sitar). Per step:
//   1. contact detection: bounding boxes, sort-and-sweep broad phase, SAT
//      narrow phase with a clipped contact manifold (narrow_phase.hpp);
//   2. contact forces: one batch call per contact model, with the shear
//      spring history kept per block pair and feature (contact_set.hpp);
//   3. central differences (seed eqs. 5-6): v(i+1/2) = v(i-1/2) + dt F/m,
//      x(i+1) = x(i) + dt v(i+1/2); angular momentum likewise, and the
//      orientation updated exactly by the quaternion of the rotation vector
//      w dt, w = I(t)^-1 L taken at the mid-step orientation. The rigid
//      bodies integrated are the free blocks, except that the blocks of a
//      clump (the scene's "clump" name) move as one non-convex body, with no
//      contacts between them (clumps.cpp).
// With "joints": "initial_faces" (the rigid-block-spring method, Kawai 1978)
// step 1 runs once: the joints are the face-face contact points that touch
// when the run starts, each fixed to both blocks (fixed_joints.cpp), and no
// contact is sought afterwards.
// Time step (seed eq. 8): dt = safety * 2/w_max * (sqrt(1 + xi^2) - xi), with
// w_max^2 bounded (Gershgorin) by J_i sum_c k_c (1 + [other block moves]),
// J_i = 1/m_i + R_i^2/I_min,i, over each block's contact points, and at least
// 8 contact points of the stiffest model for every block (so that a block in
// flight has a step that resolves its first impact).
#pragma once

#include <chrono>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "broad_phase.hpp"
#include "contact_set.hpp"
#include "narrow_phase.hpp"
#include "talus/blocks.hpp"
#include "talus/dda/contact_model.hpp"
#include "talus/motion.hpp"
#include "talus/params.hpp"
#include "talus/stage.hpp"

namespace talus::dda {

class DdaStage final : public Stage {
 public:
  static ParamSet describe();
  explicit DdaStage(const ParamValues& v);

  void setup(World& world) override;
  StageParts parts(const World&) const override { return {{"blocks"}, {}}; }
  double stable_time_step(World& world) override;
  void advance(World& world, double dt) override;
  StagePlan plan(const World& world) const override;
  // Every rank steps every block alike, with the same summed fluid forces.
  std::string why_not_on_ranks() const override { return {}; }
  std::string status(const World& world) const override;
  // Checkpoints: contact history, angular momenta, the leapfrog start flag,
  // the stable step and the energy balance (everything outside BlockSet's
  // saved fields that the next step reads).
  std::string save_state() const override;
  void load_state(std::string_view bytes) override;

  // The contact model of a block body when the host does not provide one
  // (tests). Must be called before setup; the model must outlive the stage.
  void set_contact_model(int body, ContactModel* model);

  // Quasi-static use (strength reduction): local non-viscous damping (3DEC,
  // Cundall 1987) removes alpha |F_k| sgn(v_k) from every component of each
  // dynamic block's force and torque; 0 (the default) is undamped dynamics.
  void set_local_damping(double alpha) { local_damping_ = alpha; }
  // Quasi-static use: mass scaling (3DEC's density scaling for static
  // solutions) gives each dynamic block the inertia (mass and rotational
  // inertia times one factor >= 1) that brings its own stable frequency down
  // to the slowest block's, so small blocks do not set the step. Gravity keeps
  // the true mass: equilibria are unchanged, only the path to them is not.
  void set_mass_scaling(bool on) { mass_scaling_ = on; }
  // One stable step from world.time (the host clock is not advanced).
  void relax_step(World& world);
  // Sets every block's velocity and angular momentum to zero and restarts the
  // leapfrog with a half kick (a trial restored from a saved state).
  void stop_blocks(World& world);
  // Largest unbalanced force or torque/radius of a dynamic body (a block or a
  // clump) at the last step, over the mean weight of the dynamic bodies
  // (3DEC's ratio).
  double unbalanced_ratio() const { return unbalanced_ratio_; }
  double contact_margin() const { return margin_; }
  bool fixed_joints() const { return fixed_joints_; }
  const std::vector<ContactModel*>& models() const { return models_; }
  // Per block: the block that carries the state of its rigid body (itself,
  // or the first block of its clump).
  const std::vector<std::uint32_t>& rigid_body() const { return lead_; }

  // Introspection for tests and benchmarks.
  double own_time_step() const { return dt_stable_; }
  int last_substeps() const { return last_substeps_; }
  const ContactSet& contacts() const { return contacts_; }
  struct Timing {
    double detection = 0.0, forces = 0.0, integration = 0.0;  // seconds, accumulated
    std::uint64_t steps = 0, contact_points = 0;              // sub-steps, contact points processed
  };
  const Timing& timing() const { return timing_; }

 private:
  void build_blocks(World& world);
  void build_clumps(const World& world, BlockSet& b);
  void step(World& world, BlockSet& b, double t, double h);
  void pose_blocks(BlockSet& b);
  void detect(const BlockSet& b, bool initial);
  void fix_joints(const BlockSet& b);
  // 1/m_a + 1/m_b of the rigid bodies of blocks a and b, with their inertia scales.
  double inverse_mass_sum(std::uint32_t a, std::uint32_t b) const {
    const std::uint32_t la = lead_[a], lb = lead_[b];
    return inverse_mass_[la] / inertia_scale_[la] + inverse_mass_[lb] / inertia_scale_[lb];
  }
  void place_fixed_joints(const BlockSet& b);
  void contact_forces(BlockSet& b, double h);
  void integrate(World& world, BlockSet& b, double t, double h);
  void move_kinematic(BlockSet& b, double t);
  void update_time_step();
  void update_energy(World& world, BlockSet& b);
  void check_restored(const BlockEnergy& energy) const;

  // Parameters.
  ParamValues params_;
  double safety_ = 0.5;
  bool subcycle_ = false;
  double margin_ = -1.0;  // < 0: 1% of the smallest block radius
  bool fixed_joints_ = false;  // "joints": "initial_faces"
  double local_damping_ = 0.0;
  bool mass_scaling_ = false;
  double unbalanced_ratio_ = 0.0;

  // Contact models: one per block (index into models_), and the distinct ones.
  std::vector<std::pair<int, ContactModel*>> overrides_;
  std::vector<ContactModel*> models_;
  std::vector<std::uint32_t> block_model_;

  // Per-block state the BlockSet does not carry.
  std::vector<std::uint8_t> dynamic_;            // moved by forces
  std::vector<double> inverse_mass_;
  std::vector<std::array<double, 9>> inverse_inertia_;  // body frame
  std::vector<double> agility_;                  // J = 1/m + R^2/I_min
  std::vector<Vec3> momentum_;                   // angular momentum, world frame, at the last half step
  // Rigid bodies. A body's mass properties, momentum and inertia scale sit at
  // its lead block (inverse_mass_, inverse_inertia_, agility_, momentum_,
  // inertia_scale_ are zero or one at the other blocks of a clump); its
  // centroid follows from the lead's pose, so checkpoints need nothing more.
  std::vector<std::uint32_t> lead_;              // per block: its body's lead block
  std::vector<std::uint32_t> member_begin_, members_;  // per block: the blocks of the body it leads (CSR)
  std::vector<Vec3> offset_;                     // per block: centroid from its body's centroid, body frame
  std::vector<double> body_mass_;                // per lead: its body's mass
  std::vector<double> body_radius_;              // per lead: farthest point of its body from the centroid
  std::vector<PrescribedMotion> motion_;
  std::vector<Vec3> start_position_;
  std::vector<Vec3> force_, torque_;
  bool started_ = false;

  // Geometry of this step in the world frame (flat, per-block offsets).
  std::vector<std::uint32_t> vertex_begin_, face_begin_;
  std::vector<Vec3> world_vertices_, world_normals_;
  std::vector<double> world_offsets_;
  std::vector<PosedBlock> posed_;
  std::vector<Vec3> box_lo_, box_hi_;

  // Contacts.
  BroadPhase broad_;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs_;
  struct Fresh {
    ContactPoint point;
    std::uint32_t a, b;
  };
  std::vector<std::vector<Fresh>> fresh_;         // per thread
  std::vector<NarrowPhaseScratch> scratch_;       // per thread
  std::vector<std::uint32_t> sort_order_;
  std::vector<Fresh> gathered_;
  ContactSet contacts_, previous_;
  std::vector<std::size_t> model_begin_;          // contacts_ range of each model
  std::vector<double> stiffness_sum_;             // per lead: its body's contact stiffness, for the time step
  std::vector<double> body_omega2_;               // per lead: its body's own bound on omega^2
  std::vector<double> inertia_scale_;             // per block: inertia over the true one (1 without mass scaling)
  // Fixed joints (per contact of contacts_, in its order): the contact point
  // in the body frames of a and b, a's face normal in a's body frame, the gap
  // at the start, its manifold's size (the effective mass for damping), and
  // the keys (a restored state must have the same joints).
  std::vector<Vec3> joint_on_a_, joint_on_b_, joint_normal_;
  std::vector<double> joint_gap_, joint_manifold_;  // joint_manifold_: points in the joint's manifold
  std::vector<ContactKey> joint_key_;

  BlockEnergy* energy_ = nullptr;  // world.blocks->energy, for checkpoints
  double dt_stable_ = std::numeric_limits<double>::infinity();
  int last_substeps_ = 0;
  std::size_t slipping_ = 0;
  Timing timing_;
};

}  // namespace talus::dda
