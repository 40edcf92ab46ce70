// The SPH wall-model plugin.
#include "dynamic_particles.hpp"
#include "repulsion.hpp"

TALUS_PLUGIN("talus-boundary", "0.1.0",
             talus::model_entry<talus::boundary::DynamicParticles>(
                 "boundary", "dynamic_particles", "dynamic boundary particles (DBC, as DualSPHysics)"),
             talus::model_entry<talus::boundary::Repulsion>(
                 "boundary", "repulsion", "penalty walls F = (K_s d - (v.n) K_d) n (rock-fluid seed)"));
