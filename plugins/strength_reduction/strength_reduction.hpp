// The `strength_reduction` stage: the safety factor of a block slope (seed
// pfe-ie-depth-integrated-sph-landslide §2). The joints of every block carry
// c/F, tan(phi)/F and sigma_t/F; each trial F starts at rest from the
// gravity-loaded state and is relaxed to static equilibrium by the stage's
// own DDA with local non-viscous damping (3DEC). F is bracketed and bisected.
//
// A trial fails when any of its criteria fires (all are reported):
//   no equilibrium   the unbalanced-force ratio stays above its limit for
//                    the whole step budget;
//   displacement     a block or monitor point moves farther than the limit,
//                    or its displacement grows window after window without
//                    slowing down (the seed's jump in monitor displacement);
//   slip path        free blocks are held by slipping or open joints only.
// The scene's "failure" says whether the slip path fails a trial; with fixed
// joints (a tessellated slope) the default leaves the slip path out: a block
// whose joints all yield may still hold, because its load comes from its
// neighbours' springs, which relax as it moves.
//
// One host step is one trial (the host clock is pseudo-time): progress,
// writers, checkpoints and SIGINT all act between trials. The per-trial table
// and the limit state are written when the run ends.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "dda_stage.hpp"
#include "factor_search.hpp"
#include "grid.hpp"
#include "handoff.hpp"
#include "limit_state.hpp"
#include "reduced_joint.hpp"
#include "runout_scene.hpp"
#include "talus/params.hpp"
#include "talus/stage.hpp"
#include "trial_log.hpp"

namespace talus::strength_reduction {

class StrengthReduction final : public Stage {
 public:
  static ParamSet describe();
  explicit StrengthReduction(const ParamValues& v);

  void setup(World& world) override;
  StageParts parts(const World&) const override { return {{"blocks"}, {}}; }  // its own DDA
  double stable_time_step(World& world) override;
  void advance(World& world, double dt) override;
  StagePlan plan(const World& world) const override;
  std::string why_not_on_ranks() const override {
    return "the strength reduction's trials and its hand-off to the run-out run on one process";
  }
  std::string status(const World& world) const override;
  std::string save_state() const override;
  void load_state(std::string_view bytes) override;
  std::vector<std::string> finish(World& world, const std::string& output_directory) override;

  // For tests.
  const FactorSearch& search() const { return search_; }
  const std::vector<TrialResult>& trials() const { return log_; }
  const dda::DdaStage& dda() const { return *dda_; }

 private:
  struct Monitor {
    std::uint32_t block = 0;
    Vec3 body_point, start;  // body frame; world position in the gravity-loaded state
  };

  void check_start(const World& world) const;
  void locate_monitors(const World& world);
  TrialResult relax(World& world, double factor);
  bool fails(const TrialResult& r) const;
  void choose_window();
  double displacement(const BlockSet& b) const;
  void restore_loaded_state(World& world);
  std::vector<std::string> write_handoff(const World& world, const std::string& output_directory) const;

  ParamValues params_;
  double tolerance_ = 0.005, ratio_limit_ = 1e-5, damping_ = 0.8, displacement_limit_ = -1.0;
  std::int64_t max_steps_ = 20000, window_ = 0;
  bool by_slip_path_ = true;  // "failure": "any" (no equilibrium and the displacement criteria always fail a trial)
  std::string file_;

  std::unique_ptr<dda::DdaStage> dda_;
  std::vector<std::unique_ptr<ReducedJoint>> joints_;
  std::vector<const ReducedJoint*> joint_of_body_;
  std::vector<Monitor> monitors_;

  FactorSearch search_;
  int trial_budget_ = 1;  // host steps the search needs: the gravity-loaded state and the trials
  bool loaded_ = false;   // the gravity-loaded state exists
  std::string loaded_dda_;
  std::vector<Vec3> loaded_position_;
  std::vector<Quaternion> loaded_orientation_;
  std::vector<TrialResult> log_;
  LimitState stable_, failed_;

  // Hand-off to run-out (when "handoff" is given).
  bool handoff_ = false;
  double handoff_cell_ = 0.0, handoff_margin_ = 0.0;
  BasalShear basal_shear_ = BasalShear::inverse_distance;
  bool has_dem_ = false;
  runout::Grid dem_;
  RunoutTemplate runout_template_;
};

}  // namespace talus::strength_reduction
