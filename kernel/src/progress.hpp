// What a user sees while a run goes: a progress line redrawn in place on a
// terminal, plain periodic log lines otherwise (CI logs, files).
#pragma once

#include <chrono>
#include <cstdint>
#include <string>

namespace talus {

class Progress {
 public:
  Progress(bool quiet, double interval_seconds);
  // Called every step; prints when the interval has passed.
  void update(double time, double end_time, double dt, std::uint64_t step, std::size_t particles,
              const std::string& status);
  void finish();  // ends the in-place line
  double elapsed() const;

 private:
  bool quiet_, terminal_;
  double interval_;
  std::chrono::steady_clock::time_point start_, last_;
  std::uint64_t first_step_ = 0, last_step_ = 0;
  double first_time_ = 0.0;  // simulated time at the first update (> 0 after a restart)
  bool started_ = false, drawn_ = false;
};

// Wall seconds left, from the pace since this process started: `elapsed`
// seconds took the run from simulated time `first` to `time`. A resumed run
// starts at `first` > 0 (counting from 0 made the ETA far too short).
inline double eta_seconds(double elapsed, double first, double time, double end_time) {
  const double done = time - first, left = end_time - time;
  if (!(done > 0.0) || !(left >= 0.0)) return -1.0;
  return elapsed * left / done;
}

// "1:02:03", "4:05", for durations in seconds.
std::string clock_text(double seconds);

}  // namespace talus
