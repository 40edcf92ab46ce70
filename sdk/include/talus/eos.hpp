// Equation-of-state plugins work on whole index spans of one material's
// particles (DESIGN.md principle 1): one virtual call per material per step,
// a plain vectorisable loop inside.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <numeric>
#include <span>

#include "talus/plugin.hpp"

namespace talus {

class TALUS_API EquationOfState : public Model {
 public:
  ~EquationOfState() override;

  // Called once at setup with the material's reference density rho0.
  virtual void set_reference_density(double rho0) = 0;
  // p[i] and sound speed c[i] for every i in idx.
  virtual void pressure(std::span<const Index> idx, const double* rho, double* p, double* c) const = 0;
  // The inverse, rho(p); used to start a column in hydrostatic equilibrium.
  virtual double density_at(double p) const = 0;
  // Sound speed at the reference density, for the time-step estimate.
  virtual double reference_sound_speed() const = 0;
};

// p and c from rho for the rows idx, for code written once for fields in
// double and in float: in double, the model's own batch call; in float (mixed
// precision), through chunks in double on the stack, one call of the model
// per chunk (a model reads and writes double).
inline void pressure_of(const EquationOfState& eos, std::span<const Index> idx, const double* rho, double* p,
                        double* c) {
  eos.pressure(idx, rho, p, c);
}

inline void pressure_of(const EquationOfState& eos, std::span<const Index> idx, const float* rho, float* p, float* c) {
  constexpr std::size_t chunk = 512;
  static const std::array<Index, chunk> local = [] {
    std::array<Index, chunk> k{};
    std::iota(k.begin(), k.end(), Index{0});
    return k;
  }();
  const auto chunks = static_cast<std::int64_t>((idx.size() + chunk - 1) / chunk);
#pragma omp parallel for schedule(static) if (idx.size() >= 4096)
  for (std::int64_t b = 0; b < chunks; ++b) {
    const std::size_t first = static_cast<std::size_t>(b) * chunk;
    const std::span<const Index> rows = idx.subspan(first, std::min(chunk, idx.size() - first));
    double rho_d[chunk], p_d[chunk], c_d[chunk];
    for (std::size_t k = 0; k < rows.size(); ++k) rho_d[k] = rho[rows[k]];
    eos.pressure(std::span(local).first(rows.size()), rho_d, p_d, c_d);
    for (std::size_t k = 0; k < rows.size(); ++k) {
      p[rows[k]] = static_cast<float>(p_d[k]);
      c[rows[k]] = static_cast<float>(c_d[k]);
    }
  }
}

}  // namespace talus
