// A hand-built World for DDA tests and benchmarks: block bodies from JSON
// (validated against a block-body ParamSet like the host's), contact models
// made directly, and the dda stage driven step by step.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "dda_stage.hpp"
#include "talus/blocks.hpp"
#include "talus/world.hpp"

namespace talus::dda::test {

// The parameters of a block body (name, kind, density, shape, fixed, clump,
// velocity, angular_velocity, motion), as the scene declares them.
ParamSet block_body_params();

class BlockScene {
 public:
  explicit BlockScene(Vec3 gravity = {0.0, 0.0, -9.81});

  // `body_json`: the body's scene entry without "contact"; `contact_json`: the
  // contact model's parameters with "type" (penalty_coulomb or mohr_coulomb).
  int add_block(const std::string& body_json, const std::string& contact_json);
  // Creates the stage (JSON of its parameters) and runs setup.
  DdaStage& start(const std::string& stage_json = "{}");
  // Advances n host steps of dt (dt <= 0: the stage's stable step).
  void run_steps(long n, double dt = 0.0);
  void run_until(double t_end);

  World world;
  std::unique_ptr<DdaStage> stage;
  std::vector<std::unique_ptr<ContactModel>> models;
  BlockSet& blocks() { return *world.blocks; }
};

// JSON snippets: a contact model (penalty springs of 1e8 N/m with friction
// angle phi; `extra` appends keys), a 2500 kg/m^3 block body with a shape,
// and an axis-aligned box shape.
std::string contact(double phi_deg, double damping = 0.2, const char* type = "penalty_coulomb",
                    const std::string& extra = "");
std::string block(const std::string& name, const std::string& shape, const std::string& extra = "");
std::string box(Vec3 lo, Vec3 hi);

// A box polyhedron JSON rotated by `angle_deg` about the y axis around `pivot`
// (for inclines and tilted blocks).
std::string rotated_box_json(Vec3 lo, Vec3 hi, double angle_deg, Vec3 pivot);

}  // namespace talus::dda::test
