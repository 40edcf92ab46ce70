// The fluid fields the wcsph stage reads and writes, looked up by name once
// per call (never inside a loop).
#pragma once

#include <span>

#include "talus/particles.hpp"
#include "talus/sph/fluid_terms.hpp"

namespace talus::wcsph {

inline const FieldInfo field_velocity{"velocity", FieldType::vector, "m/s", true, true};
inline const FieldInfo field_density{"density", FieldType::scalar, "kg/m^3", true, true};
inline const FieldInfo field_pressure{"pressure", FieldType::scalar, "Pa", true, false};
inline const FieldInfo field_mass{"mass", FieldType::scalar, "kg", true, true};
inline const FieldInfo field_sound_speed{"sound_speed", FieldType::scalar, "m/s", false, false};
inline const FieldInfo field_acceleration{"acceleration", FieldType::vector, "m/s^2", false, false};
inline const FieldInfo field_density_rate{"density_rate", FieldType::scalar, "kg/m^3/s", false, false};
// Three-pass non-Newtonian / turbulent viscosity (only registered when used).
inline const FieldInfo field_shear_rate{"shear_rate", FieldType::scalar, "1/s", true, false};
inline const FieldInfo field_mu_eff{"mu_eff", FieldType::scalar, "Pa s", true, false};
// Two-stage integrators: the state at t^n, kept within one step only.
// Velocity and density may be kept in float (the scene's "precision": "mixed"):
// the step adds to them a change of order dt times the rate, and rounding them
// to float costs one relative error of 6e-8 a step; positions stay in double.
inline const FieldInfo field_position_n{"position_n", FieldType::vector, "m", false, false};
inline const FieldInfo field_velocity_n{"velocity_n", FieldType::vector, "m/s", false, false, true};
inline const FieldInfo field_density_n{"density_n", FieldType::scalar, "kg/m^3", false, false, true};
// Verlet: the state at t^(n-1), carried across steps (restart state).
inline const FieldInfo field_velocity_prev{"velocity_prev", FieldType::vector, "m/s", false, true, true};
inline const FieldInfo field_density_prev{"density_prev", FieldType::scalar, "kg/m^3", false, true, true};

struct FluidFields {
  std::span<Vec3> x, v, a;
  std::span<double> rho, p, c, m, drho;
  std::span<std::int32_t> mat;

  explicit FluidFields(ParticleStore& s)
      : x(s.position()),
        v(s.vector("velocity")),
        a(s.vector("acceleration")),
        rho(s.scalar("density")),
        p(s.scalar("pressure")),
        c(s.scalar("sound_speed")),
        m(s.scalar("mass")),
        drho(s.scalar("density_rate")),
        mat(s.material()) {}

  sph::Neighbours neighbours() const {
    return {v.data(), rho.data(), p.data(), c.data(), m.data(), mat.data()};
  }
};

}  // namespace talus::wcsph
