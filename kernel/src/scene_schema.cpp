#include "scene_schema.hpp"

#include <algorithm>
#include <cmath>

#include "talus/geometry.hpp"
#include "talus/motion.hpp"
#include "text.hpp"

namespace talus {

namespace {

const std::vector<std::string> fluid_shapes = {"box", "sphere", "cylinder", "polygon", "half_space", "mesh"};
const std::vector<std::string> wall_shapes = {"box", "sphere", "cylinder", "polygon", "half_space", "box_walls", "mesh"};
const std::vector<std::string> block_shapes = {"box", "wedge", "tetrahedron", "polyhedron", "mesh"};

ParamSet domain_params() {
  ParamSet d{"domain", "the computational domain"};
  d.integer("dim").min(2).max(3).doc("2 (x-y plane, gravity along -y) or 3");
  d.vector("min").unit("m").doc("lower corner; fluid leaving it is removed");
  d.vector("max").unit("m").doc("upper corner");
  d.string_list("periodic", {"x", "y", "z"}).optional().doc("periodic axes (default none)");
  d.check([](const ParamValues& v, Diagnostics& diag) {
    const Vec3 lo = v.vector("min"), hi = v.vector("max");
    for (int a = 0; a < 3; ++a)
      if (hi[a] < lo[a] || (a < 2 && hi[a] == lo[a])) {
        diag.error(v, "max", "must be greater than min in every component");
        return;
      }
    // Every length, cell count and period is computed from max - min.
    for (int a = 0; a < 3; ++a)
      if (!std::isfinite(hi[a] - lo[a])) {
        diag.error(v, "max", std::string("the extent along ") + "xyz"[a] + ", max - min, overflows a double");
        return;
      }
  });
  return d;
}

ParamSet material_params() {
  ParamSet m{"material", "a material: reference density and its models"};
  m.real("density").unit("kg/m^3").greater_than(0.0).doc("reference density rho0");
  m.model("eos", "eos").optional().doc("equation of state (SPH fluids)");
  m.model("rheology", "rheology").optional().doc("rheology: viscosity and/or basal shear stress");
  return m;
}

ParamSet body_params() {
  ParamSet b{"body", "a fluid body, a wall or a rigid block"};
  b.string("name").doc("unique name, used in outputs and messages");
  b.choice("kind", {"fluid", "wall", "block"}).doc("fluid particles, wall (boundary) or rigid block (DDA)");
  b.string("material").optional().doc("material name (fluid: required; wall: reference density of wall particles)");
  b.real("dp").unit("m").greater_than(0.0).optional().doc("particle spacing (fluid and wall bodies)");
  declare_shape(b);
  b.vector("velocity").unit("m/s").default_value({0.0, 0.0, 0.0}, {0.0, 0.0}).doc("initial velocity");
  b.boolean("hydrostatic").default_value(false).doc(
      "fluid: start with the pressure of the fluid above each particle (every fluid body's weight: a layer under "
      "another body carries it; a body above an air gap does not) and the density the eos gives at it");
  b.model("boundary", "boundary").optional().doc("wall or block: how its surface acts on the fluid");
  b.integer("layers").min(1).optional().doc("wall: layers of wall particles (default: enough to cover the kernel)");
  b.real("density").unit("kg/m^3").greater_than(0.0).optional().doc("block: density of the rock");
  b.boolean("fixed").default_value(false).doc("block: never moves (bedrock, walls)");
  b.string("clump").optional().doc(
      "block: blocks with the same clump name move as one rigid body (a non-convex block made of convex pieces, "
      "e.g. a landslide mass cut into columns); no contacts are sought between them");
  b.vector("angular_velocity").unit("rad/s").length(3).default_value(std::vector<double>{0.0, 0.0, 0.0}).doc("block: initial angular velocity");
  b.model("contact", "contact").optional().doc("block: contact model of its faces");
  PrescribedMotion::declare(b);
  b.check([](const ParamValues& v, Diagnostics& d) {
    const std::string& kind = v.string("kind");
    const std::string& shape = v.alternative("shape");
    auto need = [&](const char* key, const char* why) {
      if (!v.has(key)) d.error(v, key, std::string("missing: a ") + kind + " body needs " + why);
    };
    auto forbid = [&](const char* key) {
      if (v.has(key)) d.error(v, key, std::string("does not apply to a ") + kind + " body");
    };
    const std::vector<std::string>& allowed =
        kind == "fluid" ? fluid_shapes : (kind == "wall" ? wall_shapes : block_shapes);
    if (std::find(allowed.begin(), allowed.end(), shape) == allowed.end())
      d.error(v, "shape", "a " + kind + " body cannot have shape '" + shape + "'", "allowed: " + text::join(allowed));
    if (kind == "fluid") {
      need("material", "a \"material\"");
      need("dp", "a particle spacing \"dp\"");
      forbid("boundary");
      forbid("contact");
      forbid("density");
      forbid("motion");
      forbid("clump");
    } else if (kind == "wall") {
      need("dp", "a particle spacing \"dp\"");
      need("boundary", "a \"boundary\" model");
      forbid("contact");
      forbid("density");
      forbid("clump");
    } else {
      need("density", "a rock \"density\"");
      forbid("dp");
      forbid("material");
    }
  });
  return b;
}

ParamSet time_params() {
  ParamSet t{"time", "the time loop"};
  t.real("end").unit("s").greater_than(0.0).doc("simulated time at which the run stops");
  t.real("dt_max").unit("s").greater_than(0.0).optional().doc("upper bound on the time step");
  t.integer("max_steps").min(1).optional().doc("stop after this many steps");
  t.integer("resort_every").min(1).default_value(int{25}).doc("re-sort fluid particles by cell every N steps (cache locality)");
  return t;
}

ParamSet output_common() {
  ParamSet o{"output", "keys every output accepts"};
  o.real("every").unit("s").greater_than(0.0).optional().doc("write every this much simulated time");
  o.integer("every_steps").min(1).optional().doc("write every N steps");
  return o;
}

ParamSet checkpoint_params() {
  ParamSet c{"checkpoint", "periodic restart files"};
  c.real("every").unit("s").greater_than(0.0).optional().doc("write a checkpoint every this much simulated time");
  c.real("every_minutes").unit("min").greater_than(0.0).optional().doc("write a checkpoint every this many wall-clock minutes");
  c.integer("keep").min(1).default_value(int{2}).doc("keep the last K checkpoints");
  return c;
}

ParamSet ranks_params() {
  ParamSet r{"ranks", "how a run on several MPI ranks shares out the particles (read only by such a run)"};
  r.choice("partition", {"RCB", "RIB", "HSFC"})
      .default_value("RCB")
      .doc("Zoltan's geometric partition: recursive coordinate bisection (boxes), recursive inertial bisection "
           "(cuts across the principal axes) or the Hilbert space-filling curve");
  r.real("rebalance_above")
      .min(1.0)
      .default_value(1.2)
      .doc("new cuts when the busiest rank's measured cost (1 + the pairs of each of its particles) exceeds the "
           "mean by this factor, checked whenever the halos are rebuilt (if the last cuts could not come within it: "
           "when it has grown by this factor over what they achieved)");
  return r;
}

ParamSet kernel_common() {
  ParamSet k{"kernel", "keys of the smoothing kernel entry"};
  k.real("h_over_dp").min(0.5).max(5.0).default_value(1.3)
      .doc("smoothing length h as a multiple of the finest dp (usually 1 to 2; beyond 5 the neighbour counts explode)");
  return k;
}

ParamSet make_scene() {
  ParamSet s{"scene", "a Talus scene"};
  s.integer("talus").min(1).max(1).doc("scene format version (1)");
  s.string("description").optional().doc("free text shown by `talus plan`");
  s.string_list("plugins").optional().doc("extra plugin libraries or folders, relative to the scene");
  s.object("domain", domain_params()).doc("the computational domain");
  s.vector("gravity").unit("m/s^2").default_value({0.0, 0.0, -9.81}, {0.0, -9.81}).doc("gravitational acceleration");
  s.model("kernel", "kernel", kernel_common()).optional().doc("smoothing kernel (required by SPH stages)");
  s.object_map("materials", material_params()).optional().doc("materials by name");
  s.object_list("bodies", body_params()).doc("fluid bodies, walls and blocks");
  s.model_list("pipeline", "stage").key("stage").doc("solver stages, in the order they advance each step");
  s.model_list("pair_terms", "pair_term")
      .optional()
      .doc("extra SPH pair terms (plugins) that the wcsph stage adds to its rates, each as its own pass, in order");
  s.object("time", time_params()).doc("the time loop");
  s.choice("precision", {"double", "mixed"})
      .default_value("double")
      .doc("how particle fields are stored: double, or mixed: the fields whose stage allows it in float (4 bytes "
           "instead of 8), positions and every other field in double; arithmetic is in double either way. wcsph "
           "keeps its integrator's saved state in float, and the fluid's velocity, density, pressure, sound speed, "
           "mass and rates where every wall model reads float (dynamic_particles), with no pair_terms and no "
           "three-pass viscosity; dynamic_particles walls with method dbc keep theirs in float. The run prints "
           "which fields are in float (summary: precision). docs/verification/precision.md compares the two on "
           "every verification case and gives the reason for the default");
  s.model_list("outputs", "writer", output_common()).optional().doc("writers and probes");
  s.object("checkpoint", checkpoint_params()).optional().doc("restart files");
  s.object("ranks", ranks_params()).optional().doc("the decomposition over MPI ranks (`mpirun -np N talus run`)");
  return s;
}

}  // namespace

const ParamSet& scene_params() {
  static const ParamSet scene = [] {
    ParamSet s = make_scene();
    return s;
  }();
  return scene;
}

}  // namespace talus
