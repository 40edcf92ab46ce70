// Boundary models: how walls act on the fluid. A boundary model is its own
// interaction pass (fluid-wall), never a branch inside the fluid-fluid force
// terms. The stage that owns the fluid calls the model's passes; the concrete
// pass interfaces live beside the stage that uses them (e.g. sph_boundary.hpp).
#pragma once

#include <span>

#include "talus/plugin.hpp"

namespace talus {

class World;

class TALUS_API Boundary : public Model {
 public:
  ~Boundary() override;

  // Called once with every wall body that names this model: build wall
  // particles or geometry from the bodies' shapes.
  virtual void setup(World& world, std::span<const int> bodies) = 0;
};

}  // namespace talus
