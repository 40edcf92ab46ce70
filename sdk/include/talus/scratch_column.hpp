// A per-particle scratch array kept in the type of the fields it derives from
// (double, or float in mixed precision, particles.hpp), such as the 1/rho a
// pass reads instead of dividing per pair: code written once for both types
// asks for as<Real>(); only the one in use holds memory.
#pragma once

#include <type_traits>
#include <vector>

namespace talus {

class ScratchColumn {
 public:
  template <class Real>
  std::vector<Real>& as() {
    static_assert(std::is_same_v<Real, double> || std::is_same_v<Real, float>, "a scratch column is double or float");
    if constexpr (std::is_same_v<Real, float>)
      return single_;
    else
      return double_;
  }
  template <class Real>
  const std::vector<Real>& as() const {
    return const_cast<ScratchColumn*>(this)->as<Real>();
  }

 private:
  std::vector<double> double_;
  std::vector<float> single_;
};

}  // namespace talus
