// SIGINT and SIGTERM during a run: caught and recorded rather than fatal, so
// that the run loop can write a checkpoint and stop cleanly at the end of a step.
#pragma once

namespace talus {

// Installs the handlers for its lifetime (clearing any signal caught before)
// and restores the previous ones when destroyed. One at a time.
class StopSignals {
 public:
  StopSignals();
  ~StopSignals();
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;

  // The signal caught so far (SIGINT or SIGTERM), or 0.
  int caught() const;

 private:
  using Handler = void (*)(int);
  Handler old_int_, old_term_;
};

}  // namespace talus
