#include "progress.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdio>

namespace talus {

std::string clock_text(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "?";
  const long s = std::lround(seconds);
  char buffer[32];
  if (s >= 3600)
    std::snprintf(buffer, sizeof buffer, "%ld:%02ld:%02ld", s / 3600, (s / 60) % 60, s % 60);
  else
    std::snprintf(buffer, sizeof buffer, "%ld:%02ld", s / 60, s % 60);
  return buffer;
}

Progress::Progress(bool quiet, double interval_seconds)
    : quiet_(quiet), terminal_(isatty(STDOUT_FILENO) == 1), interval_(interval_seconds) {
  if (interval_ <= 0) interval_ = terminal_ ? 0.25 : 10.0;
  start_ = last_ = std::chrono::steady_clock::now();
}

double Progress::elapsed() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void Progress::update(double time, double end_time, double dt, std::uint64_t step, std::size_t particles,
                      const std::string& status) {
  if (!started_) {
    started_ = true;
    first_step_ = last_step_ = step;
    first_time_ = time;
  }
  const auto now = std::chrono::steady_clock::now();
  const double since = std::chrono::duration<double>(now - last_).count();
  if (quiet_ || since < interval_) return;
  const double rate = (step - last_step_) / since;
  const double total = elapsed();
  const double fraction = end_time > 0 ? time / end_time : 0.0;
  const double eta = eta_seconds(total, first_time_, time, end_time);
  char line[320];
  std::snprintf(line, sizeof line, "t = %.4g / %.4g s (%5.1f%%)  dt = %.3g s  step %llu  %.4g steps/s  %zu particles  ETA %s%s%s",
                time, end_time, 100.0 * fraction, dt, static_cast<unsigned long long>(step), rate, particles,
                clock_text(eta).c_str(), status.empty() ? "" : "  ", status.c_str());
  if (terminal_) {
    std::printf("\r\033[K%s", line);
    drawn_ = true;
  } else {
    std::printf("%s\n", line);
  }
  std::fflush(stdout);
  last_ = now;
  last_step_ = step;
}

void Progress::finish() {
  if (drawn_) std::printf("\n");
  drawn_ = false;
  std::fflush(stdout);
}

}  // namespace talus
