// When outputs and checkpoints fall due: on multiples of their interval in
// simulated time. Shared by the output writers' schedule and the run loop's
// checkpoint schedule, so that both round the same way.
#pragma once

#include <algorithm>
#include <cmath>

namespace talus {

// The tolerance absorbs rounding in the sum of the steps, but is never a share
// of the interval that would make every step due (an end of 1e308, a 1 ms interval).
inline double schedule_eps(double end_time, double every) { return std::min(1e-9 * end_time, 1e-3 * every); }

// The first multiple of `every` after `now` (beyond `next`), in one jump.
inline double next_due(double next, double every, double now, double eps) {
  if (next > now + eps) return next;
  const double intervals = std::floor((now + eps - next) / every) + 1.0;
  return std::max(next + intervals * every, std::nextafter(now + eps, HUGE_VAL));
}

}  // namespace talus
