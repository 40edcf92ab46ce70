// Prescribed (kinematic) motion of a wall or block body: a piston
// wavemaker, a flap, a body moved at constant velocity or by a table.
//
//   "motion": { "sine":     { "direction": [1,0,0], "amplitude": 0.05, "period": 1.2, "phase": 0 } }
//               x(t) = A sin(2 pi t / T + phase) e  (piston; zero at t = 0 when phase = 0)
//   "motion": { "velocity": { "velocity": [0.1,0,0] } }
//   "motion": { "table":    { "time": [0, 1, 2], "displacement": [[0,0,0], [0.1,0,0], [0.1,0,0]] } }
//               piecewise-linear displacement, held constant after the last entry
//   "motion": { "hinge":    { "point": [..], "axis": [0,1,0], "amplitude": 0.2, "period": 1.5, "phase": 0 } }
//               flap: rotation angle a(t) = amplitude sin(2 pi t / T + phase) about the hinge line
#pragma once

#include <string>
#include <vector>

#include "talus/config.hpp"
#include "talus/params.hpp"
#include "talus/vec3.hpp"

namespace talus {

class TALUS_API PrescribedMotion {
 public:
  // Declares the optional "motion" one-of in a body's ParamSet.
  static void declare(ParamSet& body);

  PrescribedMotion() = default;  // no motion: everything stays put
  PrescribedMotion(const std::string& alternative, const ParamValues& values);

  // Position and velocity at time t of the material point that was at x0 at t = 0.
  Vec3 position(const Vec3& x0, double t) const;
  Vec3 velocity(const Vec3& x0, double t) const;
  // Where the material point that is at x at time t was at t = 0 (the inverse of position).
  Vec3 initial_position(const Vec3& x, double t) const;
  bool moves() const { return kind_ != Kind::none; }

 private:
  enum class Kind { none, sine, velocity, table, hinge };
  Kind kind_ = Kind::none;
  Vec3 direction_{}, point_{}, axis_{};
  double amplitude_ = 0.0, omega_ = 0.0, phase_ = 0.0;
  std::vector<double> times_;
  std::vector<Vec3> displacements_;
};

}  // namespace talus
