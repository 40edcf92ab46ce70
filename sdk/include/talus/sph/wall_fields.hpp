// Fields of the wall particles in World::boundary that every DBC-style
// boundary model uses. Walls and blocks share that one store, so each field
// must be declared identically by all of them: declare it here, once.
#pragma once

#include "talus/particles.hpp"

namespace talus::sph {

inline const FieldInfo wall_velocity{"velocity", FieldType::vector, "m/s", true, true};
inline const FieldInfo wall_density{"density", FieldType::scalar, "kg/m^3", true, true};
inline const FieldInfo wall_pressure{"pressure", FieldType::scalar, "Pa", true, false};
inline const FieldInfo wall_mass{"mass", FieldType::scalar, "kg", false, true};
inline const FieldInfo wall_sound_speed{"sound_speed", FieldType::scalar, "m/s", false, false};
inline const FieldInfo wall_density_rate{"density_rate", FieldType::scalar, "kg/m^3/s", false, false};
// Density at the start of the step; rebuilt by begin_step, so not restarted.
inline const FieldInfo wall_density_n{"density_n", FieldType::scalar, "kg/m^3", false, false};
// The velocity a wall particle shows the viscous terms (mDBC's mirrored v_b*),
// refilled by every fill_wall_state(); a store field so that it reaches the
// halo copies on other MPI ranks.
inline const FieldInfo wall_viscous_velocity{"viscous_velocity", FieldType::vector, "m/s", false, false};

}  // namespace talus::sph
