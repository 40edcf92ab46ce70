// The fluid fields the wcsph stage reads and writes, looked up by name once
// per call (never inside a loop).
#pragma once

#include <iterator>
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

// The fluid fields of a pass, all but the position in Real: double, or float
// in a scene of mixed precision (the stage keeps the seven fields alike).
template <class Real>
struct FluidFieldsOf {
  std::span<Vec3> x;
  std::span<VectorOf<Real>> v, a;
  std::span<Real> rho, p, c, m, drho;
  std::span<std::int32_t> mat;

  explicit FluidFieldsOf(ParticleStore& s)
      : x(s.position()),
        v(s.column<VectorOf<Real>>("velocity")),
        a(s.column<VectorOf<Real>>("acceleration")),
        rho(s.column<Real>("density")),
        p(s.column<Real>("pressure")),
        c(s.column<Real>("sound_speed")),
        m(s.column<Real>("mass")),
        drho(s.column<Real>("density_rate")),
        mat(s.material()) {}

  sph::NeighbourFields<Real> neighbours() const {
    return {v.data(), rho.data(), p.data(), c.data(), m.data(), mat.data()};
  }
};
using FluidFields = FluidFieldsOf<double>;

// 1/rho as every pass reads it, from the column or formed in place: divided
// in double, kept in the fluid's type.
template <class Real>
Real reciprocal(Real rho) {
  return static_cast<Real>(1.0 / rho);
}

// Whether the fluid's seven fields are kept in float.
inline bool fluid_in_float(const ParticleStore& s) { return s.info("density").type == FieldType::scalar_f32; }

// The fields that go to float together, in a scene of mixed precision where
// every reader of the fluid reads float (WcsphStage::single_fluid_allowed):
// their FieldInfo say double, the stage sets single_when_mixed on its copies.
inline const FieldInfo* const fluid_fields_in_float[] = {&field_velocity,    &field_density,      &field_pressure,
                                                         &field_mass,        &field_sound_speed,  &field_acceleration,
                                                         &field_density_rate};

// The seven in one type: where code widened one of them to double (by a
// require() in double), the others are widened too.
inline void keep_fluid_fields_alike(ParticleStore& s) {
  std::size_t in_float = 0;
  for (const FieldInfo* f : fluid_fields_in_float) in_float += is_single(s.info(f->name).type);
  if (in_float > 0 && in_float < std::size(fluid_fields_in_float))
    for (const FieldInfo* f : fluid_fields_in_float) s.require(*f);
}

// f(FluidFieldsOf<float>) or f(FluidFieldsOf<double>), as the store keeps them.
template <class F>
decltype(auto) with_fluid_fields(ParticleStore& s, F&& f) {
  if (fluid_in_float(s)) return f(FluidFieldsOf<float>(s));
  return f(FluidFieldsOf<double>(s));
}

}  // namespace talus::wcsph
