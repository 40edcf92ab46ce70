// The wcsph option stiff_viscosity: point_implicit (plugins/wcsph/viscosity_passes.cpp): each particle's
// acceleration divided by 1 + dt D_i, the diagonal of a backward-Euler viscous step. Checked on the flat sediment
// bed of tests/sph/sediment_bed.hpp with the seed's uncapped HBP plug (tau_y m, ~1e4 Pa s at the bed's base):
//  - the step is the acoustic one, where the explicit viscous bound makes it ~40x smaller;
//  - equilibria are kept: the bed stays at rest and unyielded below its surface, as the capped explicit bed does;
//  - the option is refused where it does not apply (arithmetic pair viscosity).
#include <gtest/gtest.h>

#include <string>

#include "../sph/sediment_bed.hpp"
#include "talus/error.hpp"

namespace {

using namespace sph_test;

std::string stage(const std::string& extra) {
  return R"({"viscosity": "laminar", "density_diffusion": "none", "courant": 0.2)" + extra + "}";
}
const std::string kHarmonic = R"(, "viscosity_mean": "harmonic")";
const std::string kPointImplicit = kHarmonic + R"(, "stiff_viscosity": "point_implicit")";

TEST(StiffViscosity, PointImplicitStepsAtTheAcousticLimitWithTheUncappedPlug) {
  SedimentBed explicit_bed(seed_sediment(), stage(kHarmonic));
  SedimentBed implicit_bed(seed_sediment(), stage(kPointImplicit));
  const double dt_explicit = explicit_bed.s.stage->stable_time_step(explicit_bed.s.world);
  const double dt_implicit = implicit_bed.s.stage->stable_time_step(implicit_bed.s.world);
  const double acoustic = kBedCourant * kBedHOverDp * kBedDp / kBedC0;
  // At rest (|D| = 0) the plug viscosity tau_y(p') m: ~1e4 Pa s at the base, C h^2 rho/mu ~ 4e-6 s.
  EXPECT_LT(dt_explicit, 0.1 * acoustic) << "explicit dt " << dt_explicit;
  EXPECT_GE(dt_implicit, 0.9 * acoustic) << "point-implicit dt " << dt_implicit;
}

TEST(StiffViscosity, PointImplicitKeepsTheBedAtRestAndUnyielded) {
  SedimentBed bed(seed_sediment(), stage(kPointImplicit));
  const BedWatch w = watch_bed(bed, 0.5, 20);
  ASSERT_GT(w.deep, 0u);
  // The same bounds as the capped explicit bed (tests/sph/test_sediment.cpp): mm/s of acoustic settling, where a
  // bed that yields or mixes moves at 0.1 - 1 m/s; at the acoustic step, 0.5 s is ~3400 steps.
  EXPECT_LT(w.steps, 4000u);
  EXPECT_LT(w.worst_speed, 0.01) << "the bed moved";
  EXPECT_LT(w.worst_shift, 0.1 * kBedDp) << "a bed particle drifted";
  EXPECT_LT(w.highest, kBedDepth) << "a sediment particle left the bed for the water";
  EXPECT_EQ(w.yielded_deep, 0u) << "of " << w.deep << " samples below the surface";
}

TEST(StiffViscosity, PointImplicitNeedsTheHarmonicPairViscosity) {
  EXPECT_THROW(SedimentBed(seed_sediment(), stage(R"(, "stiff_viscosity": "point_implicit")")), talus::InputError);
}

}  // namespace
