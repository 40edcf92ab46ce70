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
  bool started_ = false, drawn_ = false;
};

// "1:02:03", "4:05", for durations in seconds.
std::string clock_text(double seconds);

}  // namespace talus
