// Waves in a gauge record, and what they say about breaking on a slope.
//
// Zero up-crossing analysis (IAHR list of sea-state parameters, 1989; Goda,
// Random Seas and Design of Maritime Structures, sec. 2.2): the mean level of
// the record in the window is the zero; a wave runs from one up-crossing (the
// time linearly interpolated between samples) to the next; its height is its
// highest crest minus its lowest trough, its period the time between the two
// crossings.
//
// Breaker numbers (the coastline seed, its eqs. 23 and 24):
//   deep-water wavelength  L0 = g T^2 / (2 pi)
//   Iribarren              xi = tan(phi) / sqrt(H / L0)
//   Froude                 Fn = (H0 / L0) d_w f / sqrt(g / alpha),  alpha = tan(phi), f = 1/T
// with H the wave height in the surf zone, H0 offshore, d_w the still water
// depth and phi the seaward slope. Class by the seed's bands (after Battjes
// 1974): xi > 2.0 surging or collapsing, 0.4 to 2.0 plunging, < 0.4 spilling.
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <vector>

namespace talus::writers {

struct WaveStatistics {
  std::size_t waves = 0;  // complete waves in the window
  double mean_level = 0.0;
  double height = 0.0;      // mean of the waves' heights
  double max_height = 0.0;  // the highest wave
  double period = 0.0;      // mean of the waves' periods
  std::vector<double> crossings;  // the up-crossing times: wave k runs from crossings[k] to crossings[k + 1]
};

// Over the samples with time >= from; non-finite elevations (a dry gauge) are
// skipped. No complete wave: waves = 0 and the rest NaN.
WaveStatistics zero_up_crossing(std::span<const double> time, std::span<const double> elevation, double from);

struct BreakerNumbers {
  double wavelength = 0.0;  // L0
  double iribarren = 0.0;
  double froude = 0.0;
  std::string type;  // surging_or_collapsing, plunging, spilling
};

BreakerNumbers breaker_numbers(double surf_height, double offshore_height, double period, double slope_degrees,
                               double water_depth, double g);

std::string breaker_type(double iribarren);

// The linear wavelength L = 2 pi / k of period T in still water of depth d:
// omega^2 = g k tanh(k d) (Dean & Dalrymple 1991, sec. 4.4). NaN for a
// non-finite or non-positive T or d.
double linear_wavelength(double period, double depth, double g);

}  // namespace talus::writers
