// Bracketing and bisection of the safety factor: the lower end of the
// bracket must hold, the upper end must fail, then the middle of the
// bracket is tried until its width is at most the tolerance. F_s is reported
// as the middle of the final bracket (error <= tolerance / 2).
#pragma once

#include <cmath>
#include <cstdint>

namespace talus::strength_reduction {

class FactorSearch {
 public:
  // fails_at_lower, holds_at_upper: the bracket does not contain F_s.
  enum class Phase : std::uint8_t { lower, upper, bisect, done, fails_at_lower, holds_at_upper };

  FactorSearch() = default;
  FactorSearch(double lo, double hi, double tolerance)
      : lo_(lo), hi_(hi), tolerance_(tolerance),
        max_trials_(2 + static_cast<int>(std::ceil(std::log2((hi - lo) / tolerance) - 1e-12))) {}

  // Trials the search takes at most: both ends, then the bisections.
  int max_trials() const { return max_trials_; }

  double next() const {
    if (phase_ == Phase::lower) return lo_;
    if (phase_ == Phase::upper) return hi_;
    return 0.5 * (lo_ + hi_);
  }

  void record(bool failed) {
    switch (phase_) {
      case Phase::lower: phase_ = failed ? Phase::fails_at_lower : Phase::upper; return;
      case Phase::upper: phase_ = failed ? Phase::bisect : Phase::holds_at_upper; break;
      case Phase::bisect: {
        const double middle = next();
        (failed ? hi_ : lo_) = middle;
        break;
      }
      default: return;
    }
    if (phase_ == Phase::bisect && hi_ - lo_ <= tolerance_ * (1.0 + 1e-12)) phase_ = Phase::done;
  }

  Phase phase() const { return phase_; }
  bool searching() const { return phase_ == Phase::lower || phase_ == Phase::upper || phase_ == Phase::bisect; }
  double lo() const { return lo_; }
  double hi() const { return hi_; }
  double tolerance() const { return tolerance_; }
  double safety_factor() const { return 0.5 * (lo_ + hi_); }

 private:
  double lo_ = 0.5, hi_ = 4.0, tolerance_ = 0.005;
  int max_trials_ = 12;
  Phase phase_ = Phase::lower;
};

}  // namespace talus::strength_reduction
