// Water over a sediment bed (coastline seed §2.3.2, Table 3 materials) in a 2D
// tank: the HBP sediment with Drucker-Prager yield on the effective pressure
// and the plug viscosity capped at max_viscosity (Fourtakas & Rogers 2016).
//  - the cap bounds the viscous time step as documented (C h^2 rho / mu_max),
//    where the uncapped plug (tau_y m) forces a step tens of times smaller;
//  - a flat bed under still water stays at rest: no creep, no particle of the
//    bed moves into the water, and below its surface no particle is at yield
//    (mu_eff |D| < tau_y(p')).
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "sediment_bed.hpp"

namespace {

using namespace sph_test;

constexpr double kMuMax = 200.0;  // Pa s: C h^2 rho_s / mu_max = 4.3e-4 s > the acoustic C h / c0 = 1.5e-4 s
const std::string kCappedSediment = seed_sediment(", \"max_viscosity\": " + std::to_string(kMuMax));
const char* kStage = R"({"viscosity": "laminar", "viscosity_mean": "harmonic", "density_diffusion": "none",
                         "courant": 0.2})";

TEST(SedimentBed, MaxViscosityBoundsTheViscousStep) {
  SedimentBed capped(kCappedSediment, kStage), uncapped(seed_sediment(), kStage);
  const double dt_capped = capped.s.stage->stable_time_step(capped.s.world);
  const double dt_uncapped = uncapped.s.stage->stable_time_step(uncapped.s.world);
  const double h = kBedHOverDp * kBedDp;
  // Documented bound: with the cap the viscous limit is no smaller than C h^2 rho_s / mu_max, so the step is the
  // acoustic one (at rest); the first evaluation has |D| = 0, the plug's full viscosity.
  const double viscous_bound = kBedCourant * h * h * kSediment / kMuMax;
  const double acoustic = kBedCourant * h / kBedC0;
  EXPECT_GE(dt_capped, 0.95 * std::min(viscous_bound, acoustic)) << "capped dt " << dt_capped;
  const auto mu = capped.s.world.fluid.scalar("mu_eff");
  EXPECT_LE(*std::max_element(mu.begin(), mu.end()), kMuMax);
  // Uncapped, the plug viscosity tau_y(p') m (~1e4 Pa s at the bed's base) sets dt ~ 1e-5 s.
  EXPECT_LT(dt_uncapped, 0.1 * dt_capped) << "uncapped dt " << dt_uncapped << ", capped " << dt_capped;
}

// Needs the multiphase continuity form drho_i/dt = rho_i sum_j m_j/rho_j v_ij . grad W (Colagrossi &
// Landrini 2003, sph/fluid_terms.hpp): with Monaghan's sum_j m_j v_ij . grad W this bed blew up within 0.5 s
// (worst density deviation 98 %, measured 2026-11-22); with it the bed stays at rest.
TEST(SedimentBed, FlatBedUnderStillWaterStaysAtRestAndUnyielded) {
  SedimentBed bed(kCappedSediment, kStage);
  const BedWatch w = watch_bed(bed, 0.5, 50);
  ASSERT_GT(w.deep, 0u);
  // At rest the bed only carries the acoustic settling of the start: mm/s, where a bed that yields or mixes with
  // the water moves at the waves' or Rayleigh-Taylor speeds (0.1 - 1 m/s).
  EXPECT_LT(w.worst_speed, 0.01) << "the bed moved";
  EXPECT_LT(w.worst_shift, 0.1 * kBedDp) << "a bed particle drifted";
  EXPECT_LT(w.highest, kBedDepth) << "a sediment particle left the bed for the water";
  EXPECT_EQ(w.yielded_deep, 0u) << "of " << w.deep << " samples below the surface";
}

}  // namespace
