// The layout of the types the host and plugins exchange, as the including
// translation unit sees them: sizeof and alignof of every exchanged type, and
// offsetof of every member of the plain batch and input structs. The host
// compares a plugin's table (compiled into the plugin by talus_add_plugin)
// with its own, so a plugin built against edited or mixed headers is refused
// instead of reading pressure where it expects the shear rate.
//
// Add a type here when the SDK starts exchanging it.
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "talus/abi.hpp"
#include "talus/blocks.hpp"
#include "talus/dda/contact_model.hpp"
#include "talus/dda/polyhedron.hpp"
#include "talus/kernel_table.hpp"
#include "talus/mesh.hpp"
#include "talus/motion.hpp"
#include "talus/params.hpp"
#include "talus/particles.hpp"
#include "talus/plugin.hpp"
#include "talus/rheology.hpp"
#include "talus/sph/boundary_pass.hpp"
#include "talus/sph/fluid_terms.hpp"
#include "talus/stage.hpp"
#include "talus/world.hpp"
#include "talus/writer.hpp"

#define TALUS_ABI_SIZE_(T) \
  ::talus::AbiField{"sizeof(" #T ")", sizeof(T)}, ::talus::AbiField { "alignof(" #T ")", alignof(T) }
#define TALUS_ABI_AT_(T, m) \
  ::talus::AbiField { "offsetof(" #T ", " #m ")", offsetof(T, m) }

namespace talus {

constexpr auto abi_layout() {
  using dda::ContactBatch;
  using dda::MassProperties;
  using sph::FluidRates;
  using sph::FluidSettings;
  using sph::FluidView;
  using sph::Neighbours;
  using String = std::string;
  using Reals = std::vector<double>;
  return std::array{
      // The standard library types inside the exchanged ones.
      TALUS_ABI_SIZE_(String), TALUS_ABI_SIZE_(Reals),
      // The descriptor and the model table.
      TALUS_ABI_SIZE_(PluginDescriptor), TALUS_ABI_AT_(PluginDescriptor, models),
      TALUS_ABI_AT_(PluginDescriptor, model_count), TALUS_ABI_AT_(PluginDescriptor, build),
      TALUS_ABI_SIZE_(ModelEntry), TALUS_ABI_AT_(ModelEntry, describe), TALUS_ABI_AT_(ModelEntry, create),
      // Batch calls.
      TALUS_ABI_SIZE_(ViscosityInputs), TALUS_ABI_AT_(ViscosityInputs, shear_rate),
      TALUS_ABI_AT_(ViscosityInputs, pressure), TALUS_ABI_AT_(ViscosityInputs, density),
      TALUS_ABI_SIZE_(BasalInputs), TALUS_ABI_AT_(BasalInputs, depth), TALUS_ABI_AT_(BasalInputs, speed),
      TALUS_ABI_AT_(BasalInputs, density), TALUS_ABI_AT_(BasalInputs, normal_gravity),
      TALUS_ABI_SIZE_(ContactBatch), TALUS_ABI_AT_(ContactBatch, size), TALUS_ABI_AT_(ContactBatch, gap),
      TALUS_ABI_AT_(ContactBatch, normal), TALUS_ABI_AT_(ContactBatch, velocity), TALUS_ABI_AT_(ContactBatch, area),
      TALUS_ABI_AT_(ContactBatch, mass), TALUS_ABI_AT_(ContactBatch, shear), TALUS_ABI_AT_(ContactBatch, state),
      TALUS_ABI_AT_(ContactBatch, force), TALUS_ABI_AT_(ContactBatch, strain_energy),
      TALUS_ABI_AT_(ContactBatch, dissipated),
      // SPH boundary passes (the wcsph stage calls boundary plugins with these).
      TALUS_ABI_SIZE_(FluidSettings), TALUS_ABI_SIZE_(FluidView), TALUS_ABI_AT_(FluidView, position),
      TALUS_ABI_AT_(FluidView, density), TALUS_ABI_AT_(FluidView, viscosity), TALUS_ABI_AT_(FluidView, inv_density),
      TALUS_ABI_AT_(FluidView, single),
      TALUS_ABI_SIZE_(FluidRates), TALUS_ABI_AT_(FluidRates, acceleration), TALUS_ABI_AT_(FluidRates, density_rate),
      TALUS_ABI_AT_(FluidRates, visc_max), TALUS_ABI_SIZE_(Neighbours), TALUS_ABI_AT_(Neighbours, viscosity),
      // Small value types.
      TALUS_ABI_SIZE_(Vec3), TALUS_ABI_SIZE_(Quaternion), TALUS_ABI_SIZE_(BlockEnergy),
      TALUS_ABI_SIZE_(MassProperties), TALUS_ABI_SIZE_(Polyhedron),
      // Classes the host owns and plugins use through inline members.
      TALUS_ABI_SIZE_(World), TALUS_ABI_SIZE_(Material), TALUS_ABI_SIZE_(Body), TALUS_ABI_SIZE_(ParticleStore),
      TALUS_ABI_SIZE_(FieldInfo), TALUS_ABI_SIZE_(BlockSet), TALUS_ABI_SIZE_(TriangleMesh),
      TALUS_ABI_SIZE_(KernelTable), TALUS_ABI_SIZE_(PrescribedMotion), TALUS_ABI_SIZE_(OutputContext),
      TALUS_ABI_SIZE_(StagePlan), TALUS_ABI_SIZE_(ParamSpec), TALUS_ABI_SIZE_(ParamSet), TALUS_ABI_SIZE_(ParamValue),
      TALUS_ABI_SIZE_(ParamValues), TALUS_ABI_SIZE_(Diagnostics)};
}

}  // namespace talus
