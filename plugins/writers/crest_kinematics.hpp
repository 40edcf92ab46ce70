// The kinematic breaking criterion at a wave gauge: a wave breaks where the
// fluid at its crest overtakes the crest, u / c >= 1 (Perlin, Choi & Tian
// 2013, Annu. Rev. Fluid Mech. 45, sec. 3.1; a threshold near 0.85 marks the
// onset, Saket et al. 2017, J. Fluid Mech. 811).
//
// Per wave (zero up-crossing to up-crossing at the gauge):
//   c  the crest's speed over the stretch from the offshore gauge: that
//      distance over the delay between the crest times at the two gauges,
//      each the vertex of a parabola through the highest sample and its
//      neighbours. The long stretch is what makes c a travelling crest's
//      speed: before a reflecting slope the waves are partly standing, and a
//      partly standing wave's crest leads or lags the incident crest by up to
//      asin(K_r) / 2 pi of a period (K_r the reflection coefficient), which
//      between gauges a few centimetres apart swamps the delay (a steep bank
//      then shows crests 'slower than their water' that are not breaking).
//      Over the stretch the crest slows as it shoals, so c is at least the
//      local crest speed and u / c errs low (towards not breaking);
//   u  the fastest surface particle while the crest passes: the largest
//      value of the gauge's surface-speed record (velocity along the wave's
//      direction) over the samples where the surface is above its mean.
// The crest offshore is the highest sample of the offshore gauge within the
// wave period that ends at the crest here: the crest the wave had there. So
// the gauges must be less than a wavelength apart. A wave whose crest there
// is at that window's edge (a standing wave's, in phase at both gauges, or
// one passing within a sample) has no crest speed.
//
// Only a travelling crest counts. Every gravity wave up to the limiting
// steepness (Miche 1944: H/L <= 0.142 tanh kh; in shallow water H/d <= 0.78)
// moves at c^2 = (g/k) tanh kh >= g H / 0.89, so a crest measured slower than
// sqrt(g H), H the wave's own height at the gauge, is not a travelling wave's:
// it is the swash on a slope (whose front the water carries, u ~ c, breaking
// or not) or a standing motion. Such waves are left out.
#pragma once

#include <cstddef>
#include <limits>
#include <span>

#include "wave_analysis.hpp"

namespace talus::writers {

struct CrestKinematics {
  static constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  std::size_t waves = 0;        // waves with a travelling crest
  std::size_t not_travelling = 0;  // waves whose crest was slower than sqrt(g H)
  double ratio = nan;           // the largest u / c over them
  double time = nan;            // that wave's crest time at the gauge
  double crest_speed = nan;     // its c
  double particle_speed = nan;  // its u
};

// `here`: the gauge's zero up-crossing statistics of `eta_here`; `eta_offshore`
// the offshore gauge's record, `distance` behind along the waves' direction
// (> 0); `u_here` the surface-speed record; all sampled at `time`;
// g = |gravity|.
CrestKinematics crest_kinematics(std::span<const double> time, std::span<const double> eta_offshore,
                                 std::span<const double> eta_here, std::span<const double> u_here,
                                 const WaveStatistics& here, double distance, double g);

// The time of the vertex of the parabola through the samples k - 1, k, k + 1
// (k alone at either end of the record, or where the three are not a cap).
double crest_time(std::span<const double> time, std::span<const double> eta, std::size_t k);

}  // namespace talus::writers
