// The handler only records the signal: the run loop polls it once a step.
#include "stop_signals.hpp"

#include <atomic>
#include <csignal>

namespace talus {

namespace {

std::atomic<int> stop_signal{0};
extern "C" void on_stop_signal(int sig) { stop_signal.store(sig); }

}  // namespace

StopSignals::StopSignals() {
  stop_signal.store(0);
  old_int_ = std::signal(SIGINT, on_stop_signal);
  old_term_ = std::signal(SIGTERM, on_stop_signal);
}

StopSignals::~StopSignals() {
  std::signal(SIGINT, old_int_);
  std::signal(SIGTERM, old_term_);
}

int StopSignals::caught() const { return stop_signal.load(); }

}  // namespace talus
