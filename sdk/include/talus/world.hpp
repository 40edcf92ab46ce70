// Everything a stage or writer sees of a running simulation: the domain, the
// tabulated kernel, the particle stores, materials, bodies and the clock.
// Built by the host from a validated scene; stages add the fields they need.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "talus/config.hpp"
#include "talus/kernel_table.hpp"
#include "talus/parallel.hpp"
#include "talus/params.hpp"
#include "talus/particles.hpp"
#include "talus/vec3.hpp"
#include "talus/warnings.hpp"

namespace talus {

class EquationOfState;
class Rheology;
class Boundary;
class BlockSet;
class Model;
namespace sph {
class PairTerm;
}

enum class BodyKind { fluid, wall, block };
TALUS_API const char* to_string(BodyKind kind);

struct Material {
  std::string name;
  double density = 0.0;                  // reference density rho0, kg/m^3
  EquationOfState* eos = nullptr;        // owned by the host, may be null
  Rheology* rheology = nullptr;          // owned by the host, may be null
  ParamValues params;                    // the material's scene entry
};

struct Body {
  std::string name;
  BodyKind kind = BodyKind::fluid;
  int material = -1;                     // index into World::materials
  double dp = 0.0;                       // particle spacing, m
  Boundary* boundary = nullptr;          // wall bodies: the boundary model, owned by the host
  Model* contact = nullptr;              // blocks: the contact model (cast by the DDA stage), owned by the host
  ParamValues params;                    // the body's scene entry (shape, ...)
};

class TALUS_API World {
 public:
  World();
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  // Domain: particles of `fluid` that leave [lo, hi] on a closed axis are
  // removed (and counted) by the host after each step.
  int dim = 3;
  Vec3 lo{}, hi{};
  std::array<bool, 3> periodic{};
  Vec3 gravity{};

  double dp = 0.0;  // the finest body spacing
  double h = 0.0;   // smoothing length = h_over_dp * dp
  KernelTable kernel;

  ParticleStore fluid;     // SPH particles of every fluid material
  ParticleStore boundary;  // wall particles (dynamic boundary particles, ...)
  std::unique_ptr<BlockSet> blocks;  // rigid blocks, created by the DDA stage if any

  std::vector<Material> materials;
  std::vector<Body> bodies;
  // The scene's "pair_terms", owned by the host; the stage that runs them
  // sets pair_terms_run (a scene whose pipeline runs none is refused).
  std::vector<sph::PairTerm*> pair_terms;
  bool pair_terms_run = false;

  double time = 0.0;
  std::uint64_t step = 0;
  double end_time = 0.0;
  std::uint64_t removed = 0;  // fluid particles that left the domain so far
  // Fluid particles the wall models found inside a wall (each once per wall),
  // since the run or its restart began.
  std::uint64_t wall_crossings = 0;
  // Writers see a const World and may still warn: the log is not state.
  mutable WarningLog warnings;

  // Indices of the fluid particles of material m; valid until the store is
  // re-sorted or particles are removed (the host refreshes them then).
  std::span<const Index> material_particles(int m) const { return material_index_[m]; }
  void refresh_material_index();
  // Frees the index until the next refresh: a re-sort, which is followed by
  // one, needs the memory more (it would otherwise add to the run's peak).
  void release_material_index() { material_index_.clear(); }

  int find_material(std::string_view name) const;
  int find_body(std::string_view name) const;

  // The ranks this run is spread over (the serial no-op unless the host set one).
  Parallel& parallel() const { return parallel_ ? *parallel_ : serial_; }
  void set_parallel(Parallel* parallel) { parallel_ = parallel; }

 private:
  static Parallel serial_;
  Parallel* parallel_ = nullptr;
  std::vector<std::vector<Index>> material_index_;
};

}  // namespace talus
