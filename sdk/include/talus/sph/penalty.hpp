// The penalty spring of repulsive walls (rock-fluid seed §4, eq. 22), one law
// for every model that pushes fluid particles off a surface without wall
// particles (planes and meshes, block faces):
//   F = max(0, K_s d - (v . n) K_d) n,
// d the penetration into the activation layer, n the unit normal into the
// fluid, v the particle's velocity relative to the surface. The force is only
// repulsive: a particle leaving the layer faster than the spring pushes it is
// never pulled back.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

namespace talus::sph {

struct PenaltySpring {
  double stiffness = 0.0;  // K_s, N/m
  double damping = 0.0;    // K_d, N s/m

  // Magnitude along n of the force at penetration `depth` > 0 and normal
  // velocity v . n (negative while approaching the surface).
  double normal_force(double depth, double normal_velocity) const {
    return std::max(0.0, stiffness * depth - normal_velocity * damping);
  }

  // Largest stable step for a particle of `mass` on this spring: 0.2 of the
  // critical step of the damped oscillator, 2/w (sqrt(1 + z^2) - z) with
  // w = sqrt(K_s/m) and z = K_d / (2 sqrt(K_s m)). The factor 0.2 (DEM
  // practice is 0.1-0.3) leaves room for a particle in a corner, which feels
  // the springs of two or three surfaces at once.
  double stable_time_step(double mass) const {
    if (!(stiffness > 0.0) || !(mass > 0.0)) return std::numeric_limits<double>::infinity();
    const double w = std::sqrt(stiffness / mass);
    const double z = damping / (2.0 * std::sqrt(stiffness * mass));
    return 0.2 * 2.0 / w * (std::sqrt(1.0 + z * z) - z);
  }
};

}  // namespace talus::sph
