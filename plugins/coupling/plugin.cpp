// The fluid-block coupling plugin: SPH boundary models for DDA blocks.
#include "block_particles.hpp"
#include "repulsion.hpp"

TALUS_PLUGIN("talus-coupling", "0.1.0",
             talus::model_entry<talus::coupling::BlockParticles>(
                 "boundary", "block_particles",
                 "DBC boundary particles that move with a DDA block; two-way fluid-block forces"),
             talus::model_entry<talus::coupling::Repulsion>(
                 "boundary", "block_repulsion",
                 "penalty repulsion F = (Ks d - (v.n) Kd) n between fluid and a DDA block's faces (rock-fluid seed eq. 22)"));
