// An out-of-tree SPH pair term: pairwise cohesion between fluid particles
// (Becker & Teschner 2007, Proc. Symposium on Computer Animation, "Weakly
// compressible SPH for free surface flows"):
//   a_i += -kappa sum_j m_j (x_i - x_j) W_ij,
// an attraction within the kernel support that holds a free surface together
// (a simple surface-tension model). Pairwise antisymmetric: momentum is kept.
#pragma once

#include <string>

#include "talus/sph/pair_term.hpp"

namespace example {

// The pair: reads the kernel value W_ij; the pass's Sums carry `acc`.
struct CohesionPair {
  static constexpr bool uses_value = true, uses_gradient = false;
  const double* mass = nullptr;
  double kappa = 0.0;
  template <class Sums>
  void pair(const talus::sph::Pair& q, Sums& s) const {
    s.acc -= q.dx * (kappa * mass[q.j] * q.w);
  }
};

class Cohesion final : public talus::sph::PairTerm {
 public:
  static talus::ParamSet describe();
  explicit Cohesion(const talus::ParamValues& v);
  std::uint64_t add_rates(const talus::sph::PairTermInput& in) override;
  std::string pass_description() const override;

 private:
  double kappa_;
};

}  // namespace example
