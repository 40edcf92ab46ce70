// A flat bed of the coastline seed's sediment (HBP, Drucker-Prager on the effective pressure) under still sea
// water in a 2D tank, both at hydrostatic rest, and a watch of how still it stays: shared by the sediment tests
// (tests/sph/test_sediment.cpp) and the point-implicit viscosity tests (tests/rheology/test_stiff_viscosity.cpp).
#pragma once

#include <algorithm>
#include <memory>
#include <string>
#include <unordered_map>

#include "hbp.hpp"
#include "hbp_formula.hpp"
#include "newtonian.hpp"
#include "sph_world.hpp"

namespace sph_test {

inline constexpr double kBedDp = 0.01, kBedHOverDp = 1.5, kBedC0 = 20.0, kBedCourant = 0.2;
inline constexpr double kSeaWater = 1029.0, kSediment = 1922.0, kBedDepth = 0.05, kWaterDepth = 0.05;

// Coastline seed Table 3 sediment; `extra` adds keys (e.g. a max_viscosity cap) before the closing brace.
inline std::string seed_sediment(const std::string& extra = "") {
  return R"({"yield": "drucker_prager", "cohesion": 1, "friction_angle": 35, "yield_pressure": "effective",
    "pore_fluid_density": 1029, "regularisation": 100, "power_index": 1, "consistency": 0.126)" + extra + "}";
}

template <class M>
void set_rheology(SphWorld& s, int material, const std::string& json) {
  auto r = std::make_unique<M>(talus::params_from_json(M::describe(), json));
  s.world.materials[material].rheology = r.get();
  s.models.push_back(std::move(r));
}

// Tank [0, 0.4] x [0, 0.3]: 0.05 m of sediment under 0.05 m of sea water, both at hydrostatic rest.
struct SedimentBed {
  SphWorld s{2, {0, 0, 0}, {0.4, 0.3, 0}, kBedDp, kBedHOverDp};
  int water = -1, sediment = -1;

  SedimentBed(const std::string& sediment_json, const std::string& stage_json) {
    water = s.water(kBedC0, kSeaWater, "seawater");
    sediment = s.water(kBedC0, kSediment, "sediment");
    set_rheology<talus::rheology::Newtonian>(s, water, R"({"viscosity": 1.08e-3})");
    set_rheology<talus::rheology::Hbp>(s, sediment, sediment_json);
    s.fluid_box(sediment, {0, 0, 0}, {0.4, kBedDepth, 0}, true);
    s.fluid_box(water, {0, kBedDepth, 0}, {0.4, kBedDepth + kWaterDepth, 0}, true);
    // The bed's hydrostatic start from its own top misses the water above it.
    auto p = s.world.fluid.scalar("pressure");
    auto rho = s.world.fluid.scalar("density");
    const auto mat = s.world.fluid.material();
    for (std::size_t i = 0; i < p.size(); ++i)
      if (mat[i] == sediment) {
        p[i] += kSeaWater * 9.81 * kWaterDepth;
        rho[i] = s.world.materials[sediment].eos->density_at(p[i]);
      }
    s.dbc_wall(R"({"box_walls": {"min": [0, 0], "max": [0.4, 0.3], "open": ["+y"]}})", water, ", \"layers\": 3");
    s.make_stage(stage_json);
  }
};

// How still the bed stayed: worst speed and drift of a sediment particle, its highest point, and the samples below
// the bed's top two rows (every `sample_every` steps) that read yielded (mu_eff |D| >= tau_y).
struct BedWatch {
  double worst_speed = 0.0, worst_shift = 0.0, highest = 0.0;
  std::size_t yielded_deep = 0, deep = 0, steps = 0;
};

inline BedWatch watch_bed(SedimentBed& bed, double until, std::uint64_t sample_every) {
  auto& s = bed.s;
  const auto ids0 = s.world.fluid.ids();
  const auto x0 = s.world.fluid.position();
  std::unordered_map<std::uint64_t, talus::Vec3> start;
  for (std::size_t i = 0; i < ids0.size(); ++i) start[ids0[i]] = x0[i];
  const auto yield = talus::rheology::YieldStress::make(talus::rheology::YieldModel::drucker_prager, 0.0, 1.0, 35.0);
  BedWatch w;
  while (s.world.time < until) {
    s.step();
    ++w.steps;
    const auto x = s.world.fluid.position();
    const auto v = s.world.fluid.vector("velocity");
    const auto ids = s.world.fluid.ids();
    const auto mat = s.world.fluid.material();
    const auto mu = s.world.fluid.scalar("mu_eff");
    const auto gd = s.world.fluid.scalar("shear_rate");
    const auto p = s.world.fluid.scalar("pressure");
    const auto rho = s.world.fluid.scalar("density");
    for (std::size_t i = 0; i < x.size(); ++i) {
      if (mat[i] != bed.sediment) continue;
      w.worst_speed = std::max(w.worst_speed, talus::norm(v[i]));
      w.worst_shift = std::max(w.worst_shift, talus::norm(x[i] - start.at(ids[i])));
      w.highest = std::max(w.highest, x[i].y);
      if (x[i].y < kBedDepth - 2 * kBedDp && s.world.step % sample_every == 0) {
        ++w.deep;
        if (mu[i] * gd[i] >= yield.at(talus::rheology::effective_pressure(p[i], rho[i], kSeaWater))) ++w.yielded_deep;
      }
    }
  }
  return w;
}

}  // namespace sph_test
